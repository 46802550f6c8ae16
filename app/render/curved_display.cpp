#include "render/curved_display.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <variant>

namespace bounce::gl {
namespace {

constexpr int largest_split = 8;

// The PN triangle's control point next to p (towards q): p moved a third
// of the way to q, then projected onto p's tangent plane (as in
// curved_edge_point, which gives the triangle's edges).
vec3 edge_control(const vec3& p, const vec3& np, const vec3& q) {
  return (2.0 * p + q - glm::dot(q - p, np) * np) / 3.0;
}

// The PN triangle at barycentrics (w, u, v) of corners (p0, p1, p2).
vec3 pn_point(const std::array<vec3, 3>& p, const std::array<vec3, 3>& n, double w, double u, double v) {
  const vec3 b210 = edge_control(p[0], n[0], p[1]), b120 = edge_control(p[1], n[1], p[0]);
  const vec3 b021 = edge_control(p[1], n[1], p[2]), b012 = edge_control(p[2], n[2], p[1]);
  const vec3 b102 = edge_control(p[2], n[2], p[0]), b201 = edge_control(p[0], n[0], p[2]);
  const vec3 e = (b210 + b120 + b021 + b012 + b102 + b201) / 6.0;
  const vec3 b111 = e + (e - (p[0] + p[1] + p[2]) / 3.0) / 2.0;
  return p[0] * (w * w * w) + p[1] * (u * u * u) + p[2] * (v * v * v) + b210 * (3.0 * w * w * u) +
         b120 * (3.0 * w * u * u) + b201 * (3.0 * w * w * v) + b021 * (3.0 * u * u * v) + b102 * (3.0 * w * v * v) +
         b012 * (3.0 * u * v * v) + b111 * (6.0 * w * u * v);
}

double angle_degrees(const vec3& a, const vec3& b) {
  return std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
}

}  // namespace

curved_display make_curved_display(const patch_mesh& mesh, const scene* source, double degrees_per_step,
                                   std::size_t triangle_budget) {
  curved_display out;
  const std::size_t elements = mesh.element_count();
  const bool has_surfaces = mesh.element_surfaces.size() == elements;
  // The widest normal span of any element, per surface.
  std::map<int, double> span;
  for (std::size_t e = 0; e < elements; ++e) {
    const glm::ivec3& t = mesh.elements[e];
    const double widest = std::max({angle_degrees(mesh.normals[t[0]], mesh.normals[t[1]]),
                                    angle_degrees(mesh.normals[t[1]], mesh.normals[t[2]]),
                                    angle_degrees(mesh.normals[t[2]], mesh.normals[t[0]])});
    double& s = span[has_surfaces ? mesh.element_surfaces[e] : -1];
    s = std::max(s, widest);
  }
  std::map<int, int> split;  // k per surface
  std::map<int, std::size_t> surface_elements;
  for (std::size_t e = 0; e < elements; ++e) ++surface_elements[has_surfaces ? mesh.element_surfaces[e] : -1];
  double wanted = 0.0;
  for (const auto& [surface, degrees] : span) {
    const int k = std::clamp(int(std::ceil(degrees / degrees_per_step - 1e-9)), 1, largest_split);
    split[surface] = k;
    wanted += double(k) * k * double(surface_elements[surface]);
  }
  if (wanted > double(triangle_budget)) {
    // Too many: every k shrinks by one factor (flat surfaces stay at 1),
    // the largest factor that fits.
    const std::map<int, int> wished = split;
    for (double shrink = std::sqrt(double(triangle_budget) / wanted); shrink > 0.0; shrink *= 0.9) {
      double total = 0.0;
      for (auto& [surface, k] : split) {
        k = std::max(1, int(std::floor(wished.at(surface) * shrink)));
        total += double(k) * k * double(surface_elements[surface]);
      }
      if (total <= double(triangle_budget) || shrink * largest_split < 1.0) break;
    }
  }

  const auto nv = unsigned(mesh.vertex_count());
  auto sphere_of = [&](unsigned v) -> const sphere* {
    if (!source || v >= mesh.vertex_surfaces.size()) return nullptr;
    const int s = mesh.vertex_surfaces[v];
    return s >= 0 && std::size_t(s) < source->surfaces.size()
               ? std::get_if<sphere>(&source->surfaces[std::size_t(s)].geometry)
               : nullptr;
  };
  auto add_vertex = [&](vec3 p, vec3 n, const vertex_blend& blend) {
    if (const sphere* ball = sphere_of(blend.a); ball && glm::length(p - ball->center) > 0.0) {
      const vec3 out_of = glm::normalize(p - ball->center);
      p = ball->center + ball->radius * out_of;
      n = glm::dot(n, out_of) < 0.0 ? -out_of : out_of;  // a sphere seen from inside keeps its side
    }
    out.positions.push_back(p);
    out.normals.push_back(glm::length(n) > 0.0 ? glm::normalize(n) : vec3(0.0, 1.0, 0.0));
    out.blends.push_back(blend);
    return nv + unsigned(out.positions.size() - 1);
  };
  // Points inside an edge, shared by the two elements beside it: keyed by
  // the edge's ends (lower index first) and the step from the lower end.
  std::map<std::tuple<unsigned, unsigned, int>, unsigned> edge_points;
  auto edge_vertex = [&](unsigned i, unsigned j, int step, int k) {
    if (i > j) {
      std::swap(i, j);
      step = k - step;
    }
    const auto key = std::make_tuple(i, j, step);
    if (const auto found = edge_points.find(key); found != edge_points.end()) return found->second;
    const double t = double(step) / k;
    const vec3 p = curved_edge_point(mesh.positions[i], mesh.normals[i], mesh.positions[j], mesh.normals[j], t);
    const vec3 n = (1.0 - t) * mesh.normals[i] + t * mesh.normals[j];
    const unsigned index = add_vertex(p, n, vertex_blend{i, j, j, float(1.0 - t), float(t), 0.0f});
    edge_points.emplace(key, index);
    return index;
  };

  out.first.reserve(elements + 1);
  out.first.push_back(0);
  std::vector<unsigned> grid;
  for (std::size_t e = 0; e < elements; ++e) {
    const glm::ivec3& t = mesh.elements[e];
    const unsigned c[3] = {unsigned(t[0]), unsigned(t[1]), unsigned(t[2])};
    const int k = split[has_surfaces ? mesh.element_surfaces[e] : -1];
    if (k <= 1) {
      out.triangles.insert(out.triangles.end(), {c[0], c[1], c[2]});
      out.outline.insert(out.outline.end(), {c[0], c[1], c[1], c[2], c[2], c[0]});
      out.first.push_back(out.first.back() + 1);
      continue;
    }
    const std::array<vec3, 3> p = {mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]]};
    const std::array<vec3, 3> n = {mesh.normals[c[0]], mesh.normals[c[1]], mesh.normals[c[2]]};
    // Grid point (i, j): barycentrics w = (k - i - j) / k on c0, u = i / k on c1, v = j / k on c2.
    auto at = [&](int i, int j) -> unsigned& { return grid[std::size_t(j) * (k + 1) + i]; };
    grid.assign(std::size_t(k + 1) * (k + 1), 0);
    for (int j = 0; j <= k; ++j)
      for (int i = 0; i + j <= k; ++i) {
        const int l = k - i - j;
        if (l == k)
          at(i, j) = c[0];
        else if (i == k)
          at(i, j) = c[1];
        else if (j == k)
          at(i, j) = c[2];
        else if (j == 0)
          at(i, j) = edge_vertex(c[0], c[1], i, k);
        else if (l == 0)
          at(i, j) = edge_vertex(c[1], c[2], j, k);
        else if (i == 0)
          at(i, j) = edge_vertex(c[2], c[0], l, k);
        else {
          const double w = double(l) / k, u = double(i) / k, v = double(j) / k;
          at(i, j) = add_vertex(pn_point(p, n, w, u, v), w * n[0] + u * n[1] + v * n[2],
                                vertex_blend{c[0], c[1], c[2], float(w), float(u), float(v)});
        }
      }
    std::size_t count = 0;
    for (int j = 0; j < k; ++j)
      for (int i = 0; i + j < k; ++i) {
        out.triangles.insert(out.triangles.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
        ++count;
        if (i + j + 1 < k) {
          out.triangles.insert(out.triangles.end(), {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
          ++count;
        }
      }
    out.first.push_back(out.first.back() + count);
    for (int s = 0; s < k; ++s)
      out.outline.insert(out.outline.end(),
                         {at(s, 0), at(s + 1, 0), at(k - s, s), at(k - s - 1, s + 1), at(0, k - s), at(0, k - s - 1)});
  }
  return out;
}

}  // namespace bounce::gl
