#include "mesh/a_priori_refinement.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "scene/scene_info.h"

namespace bounce {
namespace {

std::uint64_t edge_key(int a, int b) {
  return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
}

// How many elements use each edge: 1 on a surface's boundary (vertices are
// split between surfaces, so surfaces never share an edge).
std::unordered_map<std::uint64_t, int> edge_uses(const patch_mesh& mesh) {
  std::unordered_map<std::uint64_t, int> uses;
  uses.reserve(mesh.element_count() * 2);
  for (const glm::ivec3& t : mesh.elements)
    for (int k = 0; k < 3; ++k) ++uses[edge_key(t[k], t[(k + 1) % 3])];
  return uses;
}

// Elements bucketed by the cells of a uniform grid their bounding boxes
// (grown by `margin`) overlap: candidates for point queries.
struct element_grid {
  double cell;
  std::unordered_map<std::uint64_t, std::vector<int>> cells;

  static std::uint64_t key(long long x, long long y, long long z) {
    return (std::uint64_t(x & 0x1FFFFF) << 42) | (std::uint64_t(y & 0x1FFFFF) << 21) | std::uint64_t(z & 0x1FFFFF);
  }
  long long index(double c) const { return std::llround(std::floor(c / cell)); }

  element_grid(const patch_mesh& mesh, double cell_size, double margin) : cell(cell_size) {
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
      vec3 lo(1e300), hi(-1e300);
      for (int k = 0; k < 3; ++k) {
        lo = glm::min(lo, mesh.positions[mesh.elements[e][k]]);
        hi = glm::max(hi, mesh.positions[mesh.elements[e][k]]);
      }
      lo -= vec3(margin);
      hi += vec3(margin);
      for (long long x = index(lo.x); x <= index(hi.x); ++x)
        for (long long y = index(lo.y); y <= index(hi.y); ++y)
          for (long long z = index(lo.z); z <= index(hi.z); ++z) cells[key(x, y, z)].push_back(int(e));
    }
  }

  const std::vector<int>* at(const vec3& p) const {
    auto it = cells.find(key(index(p.x), index(p.y), index(p.z)));
    return it == cells.end() ? nullptr : &it->second;
  }
};

bool emits(const patch_mesh& mesh, std::size_t e) {
  return channel_sum(mesh.vertex_emission[mesh.elements[e][0]]) > 0.0;
}

std::vector<int> sorted_unique(std::vector<int> marks) {
  std::sort(marks.begin(), marks.end());
  marks.erase(std::unique(marks.begin(), marks.end()), marks.end());
  return marks;
}

}  // namespace

double adaptive_start_edge(const scene& s) {
  return 1.5 * default_max_edge(s);
}

std::vector<int> contact_marks(const patch_mesh& mesh, double min_edge) {
  // A surface's boundary edge lying on the inside of another surface's
  // element (not on that surface's own boundary: walls meeting at a corner
  // are not a contact) marks both elements. Points are sampled along the
  // boundary edge at half the minimum edge. Where the mesher cut the
  // ground under a solid out, the contact is its outline: a boundary edge
  // along it marks its element (the ground's and the solid's alike).
  const auto uses = edge_uses(mesh);
  std::vector<int> marks;
  const double close = 1e-6 * mesh.scene_diagonal;
  if (!mesh.contact_outline.empty()) {
    std::unordered_map<std::uint64_t, std::vector<int>> outline_cells;
    const double cell = std::max(mesh.max_edge, mesh.scene_diagonal / 64.0);
    auto index = [&](double c) { return std::llround(std::floor(c / cell)); };
    for (std::size_t i = 0; i < mesh.contact_outline.size(); ++i) {
      const vec3 lo = glm::min(mesh.contact_outline[i][0], mesh.contact_outline[i][1]) - vec3(close);
      const vec3 hi = glm::max(mesh.contact_outline[i][0], mesh.contact_outline[i][1]) + vec3(close);
      for (long long x = index(lo.x); x <= index(hi.x); ++x)
        for (long long y = index(lo.y); y <= index(hi.y); ++y)
          for (long long z = index(lo.z); z <= index(hi.z); ++z)
            outline_cells[element_grid::key(x, y, z)].push_back(int(i));
    }
    auto on_outline = [&](const vec3& p, const std::array<vec3, 2>& s) {
      const vec3 d = s[1] - s[0];
      const double t = std::clamp(glm::dot(p - s[0], d) / std::max(glm::dot(d, d), 1e-300), 0.0, 1.0);
      return glm::length(p - (s[0] + d * t)) < close;
    };
    for (std::size_t e = 0; e < mesh.element_count(); ++e) {
      if (element_longest_edge(mesh, int(e)) <= min_edge) continue;
      const glm::ivec3 t = mesh.elements[e];
      for (int k = 0; k < 3; ++k) {
        const vec3 pa = mesh.positions[t[k]], pb = mesh.positions[t[(k + 1) % 3]];
        if (uses.at(edge_key(t[k], t[(k + 1) % 3])) != 1) continue;
        const vec3 mid = 0.5 * (pa + pb);
        const auto it = outline_cells.find(element_grid::key(index(mid.x), index(mid.y), index(mid.z)));
        if (it == outline_cells.end()) continue;
        bool along = false;
        for (int i : it->second)
          along = along || (on_outline(pa, mesh.contact_outline[std::size_t(i)]) &&
                            on_outline(pb, mesh.contact_outline[std::size_t(i)]));
        if (along) {
          marks.push_back(int(e));
          break;
        }
      }
    }
  }
  std::vector<bool> on_surface_boundary(mesh.vertex_count(), false);
  for (const glm::ivec3& t : mesh.elements)
    for (int k = 0; k < 3; ++k)
      if (uses.at(edge_key(t[k], t[(k + 1) % 3])) == 1)
        on_surface_boundary[t[k]] = on_surface_boundary[t[(k + 1) % 3]] = true;
  const double tolerance = 1e-6 * mesh.scene_diagonal;
  const element_grid grid(mesh, std::max(mesh.max_edge, mesh.scene_diagonal / 64.0), tolerance);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (uses.at(edge_key(a, b)) != 1) continue;
      const vec3 pa = mesh.positions[a], pb = mesh.positions[b];
      // (capped: a boundary edge is never longer than the starting edge, and
      // the mesher refuses a minimum edge below max_edge / 256)
      const int samples = int(std::clamp(std::ceil(glm::length(pb - pa) / (0.5 * min_edge)) + 1.0, 2.0, 1024.0));
      bool touched = false;
      for (int i = 0; i < samples; ++i) {
        const vec3 q = pa + (pb - pa) * (double(i) / (samples - 1));
        const std::vector<int>* candidates = grid.at(q);
        if (!candidates) continue;
        for (int other : *candidates) {
          const glm::ivec3 o = mesh.elements[other];
          if (o[0] == a || o[1] == a || o[2] == a || o[0] == b || o[1] == b || o[2] == b) continue;
          if (std::abs(glm::dot(mesh.element_normals[other], q - mesh.positions[o[0]])) > tolerance) continue;
          const vec3 w = barycentric(mesh, other, q);
          if (std::min({w[0], w[1], w[2]}) < -1e-9) continue;
          // On the other surface's boundary (w[j] ~ 0 is the edge opposite j)?
          // (or at one of its boundary vertices)?
          bool on_boundary = false;
          for (int j = 0; j < 3; ++j) {
            if (std::abs(w[j]) < 1e-6 && uses.at(edge_key(o[(j + 1) % 3], o[(j + 2) % 3])) == 1) on_boundary = true;
            if (std::abs(w[j] - 1.0) < 1e-6 && on_surface_boundary[o[j]]) on_boundary = true;
          }
          if (on_boundary) continue;
          if (element_longest_edge(mesh, other) > min_edge) marks.push_back(other);
          touched = true;
        }
      }
      if (touched && element_longest_edge(mesh, e) > min_edge) marks.push_back(int(e));
    }
  }
  return sorted_unique(std::move(marks));
}

std::vector<int> emitter_marks(const patch_mesh& mesh, double min_edge) {
  // The form factor to an emitter varies as 1/r^2: an element in front of
  // an emitter (and facing it) should be no larger than its distance to it.
  // Emitters are taken by patch (their outlines), far fewer than elements.
  struct emitter {
    vec3 center, normal;
    double radius;
  };
  std::vector<emitter> emitters;
  std::vector<bool> patch_emits(mesh.patch_count(), false);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    if (emits(mesh, e)) patch_emits[mesh.element_patches[e]] = true;
  for (std::size_t p = 0; p < mesh.patch_count(); ++p) {
    if (!patch_emits[p]) continue;
    const auto& c = mesh.patch_corners[p];
    const vec3 center = (c[0] + c[1] + c[2]) / 3.0;
    double radius = 0.0;
    for (const vec3& corner : c) radius = std::max(radius, glm::length(corner - center));
    emitters.push_back({center, mesh.patch_normals[p], radius});
  }
  std::vector<int> marks;
  if (emitters.empty()) return marks;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    if (emits(mesh, e)) continue;
    const double size = element_longest_edge(mesh, e);
    if (size <= min_edge) continue;
    const vec3 c = element_centroid(mesh, e);
    for (const emitter& em : emitters) {
      const vec3 d = c - em.center;
      if (glm::dot(em.normal, d) <= 0.0 || glm::dot(mesh.element_normals[e], d) >= 0.0) continue;
      if (size > glm::length(d) - em.radius) {
        marks.push_back(int(e));
        break;
      }
    }
  }
  return marks;
}

bool refine_a_priori(patch_mesh& mesh, double min_edge, refinement_pass& report, std::string& error) {
  report.elements_before = mesh.element_count();
  const std::size_t vertices_before = mesh.vertex_count();
  std::vector<int> origin;
  for (;;) {
    std::vector<int> contact = contact_marks(mesh, min_edge);
    std::vector<int> emitter = emitter_marks(mesh, min_edge);
    report.contact += contact.size();
    report.emitter += emitter.size();
    contact.insert(contact.end(), emitter.begin(), emitter.end());
    contact = sorted_unique(std::move(contact));
    if (contact.empty()) break;
    if (!refine_patch_mesh(mesh, contact, min_edge, origin, error)) return false;
  }
  report.elements_after = mesh.element_count();
  report.new_vertices = mesh.vertex_count() - vertices_before;
  return true;
}

}  // namespace bounce
