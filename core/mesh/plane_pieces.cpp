// Planes, pieces and their re-triangulation (plane_pieces.h).
#include "mesh/plane_pieces.h"

#include "base/random_stream.h"
#include "mesh/coplanar_cut.h"
#include "mesh/polygon_triangulation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <tuple>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace bounce {

vec3 triangle_cross(const triangle_mesh& m, int t) {
  const glm::ivec3 tri = m.triangles[t];
  return glm::cross(m.positions[tri[1]] - m.positions[tri[0]], m.positions[tri[2]] - m.positions[tri[0]]);
}

vec3 centroid(const triangle_mesh& m, int t) {
  const glm::ivec3 tri = m.triangles[t];
  return (m.positions[tri[0]] + m.positions[tri[1]] + m.positions[tri[2]]) / 3.0;
}

// Groups the flat surfaces' triangles into planes.
std::vector<plane_group> plane_groups(const std::vector<triangle_mesh>& tessellated, const std::vector<bool>& flat,
                                      double tolerance) {
  // By normal first: a hash on the normal in cells of the angle tolerance,
  // the neighbouring cells searched too.
  std::vector<plane_group> by_normal;
  struct cell_hash {
    std::size_t operator()(std::uint64_t key) const { return std::size_t(murmur_mix64(key)); }
  };
  std::unordered_map<std::uint64_t, std::vector<int>, cell_hash> cells;
  const double cos_max = std::cos(coplanar_max_angle);
  for (std::size_t s = 0; s < tessellated.size(); ++s) {
    if (!flat[s]) continue;
    const triangle_mesh& m = tessellated[s];
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const vec3 cross = triangle_cross(m, int(t));
      const double length = glm::length(cross);
      if (!(length > 0.0) || !std::isfinite(length)) continue;
      const vec3 n = cross / length;
      // A unit normal's cells run to 1 / coplanar_max_angle on each axis:
      // far inside 21 bits each.
      const auto cell = [&](const vec3& v) {
        return std::make_tuple(std::llround(v.x / coplanar_max_angle), std::llround(v.y / coplanar_max_angle),
                               std::llround(v.z / coplanar_max_angle));
      };
      const auto packed = [](long long x, long long y, long long z) {
        constexpr long long bias = 1 << 20;
        return (std::uint64_t(x + bias) << 42) | (std::uint64_t(y + bias) << 21) | std::uint64_t(z + bias);
      };
      const auto [cx, cy, cz] = cell(n);
      int found = -1;
      const auto search = [&](long long x, long long y, long long z) {
        auto it = cells.find(packed(x, y, z));
        if (it == cells.end()) return;
        for (int g : it->second)
          if (glm::dot(by_normal[std::size_t(g)].normal, n) >= cos_max) {
            found = g;
            return;
          }
      };
      search(cx, cy, cz);  // the normal's own cell first: it nearly always holds the group
      for (long long dx = -1; dx <= 1 && found < 0; ++dx)
        for (long long dy = -1; dy <= 1 && found < 0; ++dy)
          for (long long dz = -1; dz <= 1 && found < 0; ++dz)
            if (dx != 0 || dy != 0 || dz != 0) search(cx + dx, cy + dy, cz + dz);
      if (found < 0) {
        found = int(by_normal.size());
        by_normal.push_back({n, {}});
        cells[packed(cx, cy, cz)].push_back(found);
      }
      by_normal[found].triangles.push_back({int(s), int(t), 0.0});
    }
  }
  // Then by offset along the normal: sorted, split where neighbours are
  // farther apart than the tolerance.
  std::vector<plane_group> planes;
  for (plane_group& g : by_normal) {
    for (triangle_ref& r : g.triangles) r.offset = glm::dot(g.normal, centroid(tessellated[r.surface], r.triangle));
    std::sort(g.triangles.begin(), g.triangles.end(),
              [](const triangle_ref& a, const triangle_ref& b) { return a.offset < b.offset; });
    for (std::size_t i = 0; i < g.triangles.size(); ++i) {
      if (i == 0 || g.triangles[i].offset - g.triangles[i - 1].offset > tolerance) planes.push_back({g.normal, {}});
      planes.back().triangles.push_back(g.triangles[i]);
    }
  }
  return planes;
}

ClipperLib::Paths piece_paths(const triangle_mesh& m, const std::vector<int>& triangles, const plane_frame& frame) {
  ClipperLib::Paths paths;
  for (int t : triangles) {
    ClipperLib::Path path;
    for (int k = 0; k < 3; ++k) path.push_back(frame.project(m.positions[m.triangles[t][k]]));
    if (ClipperLib::Area(path) > 0.0) paths.push_back(std::move(path));
  }
  return paths;
}

// A ring's bounding box in the integer frame (left/top the least X/Y).
ClipperLib::IntRect box_of(const ClipperLib::Path& path) {
  ClipperLib::IntRect r{path[0].X, path[0].Y, path[0].X, path[0].Y};
  for (const ClipperLib::IntPoint& q : path) {
    r.left = std::min(r.left, q.X);
    r.top = std::min(r.top, q.Y);
    r.right = std::max(r.right, q.X);
    r.bottom = std::max(r.bottom, q.Y);
  }
  return r;
}

double tree_area(const ClipperLib::PolyTree& tree) {
  double area = 0.0;
  for (ClipperLib::PolyNode* node = tree.GetFirst(); node; node = node->GetNext())
    area += std::abs(ClipperLib::Area(node->Contour)) * (node->IsHole() ? -1.0 : 1.0);
  return area;
}

// Triangulates `region` (Clipper's rings, holes as children) into
// `added`. False if some ring cannot be triangulated.
bool triangulate_region(const ClipperLib::PolyTree& region, std::vector<std::array<int_point, 3>>& added) {
  auto to_points = [](const ClipperLib::Path& path, bool counter_clockwise) {
    std::vector<int_point> out;
    for (const ClipperLib::IntPoint& q : path) out.push_back({q.X, q.Y});
    if ((ClipperLib::Area(path) > 0.0) != counter_clockwise) std::reverse(out.begin(), out.end());
    return out;
  };
  const std::size_t before = added.size();
  for (ClipperLib::PolyNode* node = region.GetFirst(); node; node = node->GetNext()) {
    if (node->IsHole() || node->Contour.size() < 3) continue;
    std::vector<int_point> all = to_points(node->Contour, true);
    std::vector<std::vector<int_point>> holes;
    for (ClipperLib::PolyNode* child : node->Childs)
      if (child->Contour.size() >= 3) holes.push_back(to_points(child->Contour, false));
    const std::vector<std::array<int, 3>> triangles = triangulate_with_holes(all, holes);
    if (triangles.empty()) {
      added.resize(before);
      return false;
    }
    for (const auto& h : holes) all.insert(all.end(), h.begin(), h.end());
    for (const auto& t : triangles) added.push_back({all[t[0]], all[t[1]], all[t[2]]});
  }
  return true;
}

// Replaces piece p's triangles in this plane with `added` (integer
// corners in the plane's frame).
void replace_with(triangle_mesh& m, const piece& p, const std::vector<std::array<int_point, 3>>& added,
                  const plane_frame& frame, const std::map<std::pair<long long, long long>, vec2>& cover_corners,
                  std::vector<bool>& removed, const std::vector<int>* origins) {
  // The piece's own corners keep their exact vertices, so that its boundary
  // still meets its other faces; points where the cover's outline crosses
  // are interpolated from the piece's triangle they lie deepest inside.
  std::map<std::pair<long long, long long>, int> corners;
  for (int t : p.triangles)
    for (int k = 0; k < 3; ++k) {
      const ClipperLib::IntPoint q = frame.project(m.positions[m.triangles[t][k]]);
      corners.try_emplace({q.X, q.Y}, m.triangles[t][k]);
    }
  std::map<std::pair<long long, long long>, int> made;
  auto vertex_at = [&](const int_point& q, std::span<const int> candidates) {
    const auto [it, fresh] = made.try_emplace({q.x, q.y}, int(m.positions.size()));
    if (!fresh) return it->second;
    if (auto c = corners.find({q.x, q.y}); c != corners.end()) return it->second = c->second;
    // A corner of the cover (the light's) is placed where it is exactly,
    // not on the integer grid (which is 2^-29 of the scene's extent).
    const auto exact = cover_corners.find({q.x, q.y});
    const vec2 x = exact != cover_corners.end() ? exact->second : frame.plane_point({q.x, q.y});
    int best = candidates.front();
    double best_depth = -INFINITY;
    vec3 best_weights(1.0, 0.0, 0.0);
    for (int t : candidates) {
      vec2 c[3];
      for (int k = 0; k < 3; ++k) c[k] = frame.exact(m.positions[m.triangles[t][k]]);
      const double area = (c[1].x - c[0].x) * (c[2].y - c[0].y) - (c[1].y - c[0].y) * (c[2].x - c[0].x);
      if (!(area > 0.0)) continue;
      vec3 w;
      for (int k = 0; k < 3; ++k) {
        const vec2 a = c[(k + 1) % 3], b = c[(k + 2) % 3];
        w[k] = ((b.x - a.x) * (x.y - a.y) - (b.y - a.y) * (x.x - a.x)) / area;
      }
      if (std::min({w[0], w[1], w[2]}) > best_depth) {
        best_depth = std::min({w[0], w[1], w[2]});
        best = t;
        best_weights = w;
      }
    }
    vec3 w = glm::clamp(best_weights, 0.0, 1.0);
    w /= std::max(w.x + w.y + w.z, 1e-300);
    const glm::ivec3 tri = m.triangles[best];
    const vec3 n = w[0] * m.normals[tri[0]] + w[1] * m.normals[tri[1]] + w[2] * m.normals[tri[2]];
    m.positions.push_back(w[0] * m.positions[tri[0]] + w[1] * m.positions[tri[1]] + w[2] * m.positions[tri[2]]);
    m.normals.push_back(glm::length(n) > 0.0 ? glm::normalize(n) : m.normals[tri[0]]);
    m.uvs.push_back(w[0] * m.uvs[tri[0]] + w[1] * m.uvs[tri[1]] + w[2] * m.uvs[tri[2]]);
    return it->second;
  };
  for (int t : p.triangles) removed[t] = true;
  for (std::size_t i = 0; i < added.size(); ++i) {
    const auto& t = added[i];
    const std::span<const int> candidates =
        origins ? std::span<const int>(&(*origins)[i], 1) : std::span<const int>(p.triangles);
    const glm::ivec3 tri(vertex_at(t[0], candidates), vertex_at(t[1], candidates), vertex_at(t[2], candidates));
    m.triangles.push_back(tri);
    m.materials.push_back(p.material);
    removed.push_back(false);
  }
}

// Replaces piece p's triangles in this plane with a triangulation of
// `region`. False (nothing changed) if the region cannot be triangulated.
bool replace_piece(triangle_mesh& m, const piece& p, const ClipperLib::PolyTree& region, const plane_frame& frame,
                   const std::map<std::pair<long long, long long>, vec2>& cover_corners, std::vector<bool>& removed) {
  std::vector<std::array<int_point, 3>> added;
  if (!triangulate_region(region, added)) return false;
  replace_with(m, p, added, frame, cover_corners, removed);
  return true;
}

// Drops the triangles that replace_piece replaced.
void drop_removed(std::vector<triangle_mesh>& tessellated, const std::vector<std::vector<bool>>& removed) {
  for (std::size_t s = 0; s < tessellated.size(); ++s) {
    triangle_mesh& m = tessellated[s];
    std::size_t kept = 0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      if (!removed[s][t]) {
        m.triangles[kept] = m.triangles[t];
        m.materials[kept] = m.materials[t];
        ++kept;
      }
    m.triangles.resize(kept);
    m.materials.resize(kept);
  }
}

}  // namespace bounce
