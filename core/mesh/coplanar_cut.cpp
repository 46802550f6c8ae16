// Coplanar overlaps cut out of the surface behind (coplanar_cut.h). The
// polygon boolean is Clipper's (Debian's libpolyclipping, integer
// coordinates); the triangulation of what is left is ear clipping with the
// holes bridged in, on the same integers, so every orientation test is exact.
#include "mesh/coplanar_cut.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <clipper.hpp>
#include <glm/geometric.hpp>

namespace bounce {
namespace {

// Exact while coordinates stay within +-2^29: differences within 2^30,
// products within 2^60, their difference within 2^61.
long long orient(const int_point& a, const int_point& b, const int_point& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

int sign(long long v) {
  return (v > 0) - (v < 0);
}

bool on_segment(const int_point& a, const int_point& b, const int_point& p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

// Whether segments ab and cd share any point (touching included).
bool segments_meet(const int_point& a, const int_point& b, const int_point& c, const int_point& d) {
  const int o1 = sign(orient(a, b, c)), o2 = sign(orient(a, b, d));
  const int o3 = sign(orient(c, d, a)), o4 = sign(orient(c, d, b));
  if (o1 != o2 && o3 != o4) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) || (o3 == 0 && on_segment(c, d, a)) ||
         (o4 == 0 && on_segment(c, d, b));
}

// Whether direction d from corner b lies strictly inside the polygon's
// interior wedge there (counter-clockwise ring: a before b, c after).
bool inside_wedge(const int_point& a, const int_point& b, const int_point& c, const int_point& towards) {
  const int_point o{0, 0};
  const int_point to_c{c.x - b.x, c.y - b.y}, to_a{a.x - b.x, a.y - b.y}, d{towards.x - b.x, towards.y - b.y};
  if (orient(a, b, c) > 0) return orient(o, to_c, d) > 0 && orient(o, d, to_a) > 0;  // convex corner
  return orient(o, to_c, d) > 0 || orient(o, d, to_a) > 0;                           // reflex (or straight)
}

double smallest_angle(const int_point& a, const int_point& b, const int_point& c) {
  const vec2 p[3] = {vec2(double(a.x), double(a.y)), vec2(double(b.x), double(b.y)), vec2(double(c.x), double(c.y))};
  double smallest = INFINITY;
  for (int k = 0; k < 3; ++k) {
    const vec2 u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
    const double cosine = glm::dot(u, v) / std::max(glm::length(u) * glm::length(v), 1e-300);
    smallest = std::min(smallest, std::acos(std::clamp(cosine, -1.0, 1.0)));
  }
  return smallest;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate_with_holes(const std::vector<int_point>& outer,
                                                       const std::vector<std::vector<int_point>>& holes) {
  std::vector<int_point> points = outer;
  std::vector<int> ring(outer.size());
  for (std::size_t i = 0; i < outer.size(); ++i) ring[i] = int(i);
  std::vector<std::vector<int>> pending;  // holes not yet bridged, as indices into points
  for (const auto& hole : holes) {
    std::vector<int> h;
    for (const int_point& p : hole) {
      h.push_back(int(points.size()));
      points.push_back(p);
    }
    if (h.size() >= 3) pending.push_back(std::move(h));
  }
  // Holes in order of their leftmost point; each is bridged from that point
  // to the nearest ring corner the bridge can reach without meeting an edge
  // of the ring or of a hole still pending. The ring then runs out along the
  // bridge, around the hole and back (both bridge ends appear twice).
  auto leftmost = [&](const std::vector<int>& h) {
    return int(std::min_element(h.begin(), h.end(),
                                [&](int a, int b) {
                                  return std::tie(points[a].x, points[a].y) < std::tie(points[b].x, points[b].y);
                                }) -
               h.begin());
  };
  std::sort(pending.begin(), pending.end(), [&](const std::vector<int>& a, const std::vector<int>& b) {
    const int_point& pa = points[a[leftmost(a)]];
    const int_point& pb = points[b[leftmost(b)]];
    return std::tie(pa.x, pa.y) < std::tie(pb.x, pb.y);
  });
  for (std::size_t k = 0; k < pending.size(); ++k) {
    const std::vector<int>& hole = pending[k];
    const int start = leftmost(hole);
    const int_point h = points[hole[start]];
    auto bridge_is_clear = [&](const int_point& v) {
      auto clear_of = [&](const std::vector<int>& loop) {
        for (std::size_t i = 0; i < loop.size(); ++i) {
          const int_point& a = points[loop[i]];
          const int_point& b = points[loop[(i + 1) % loop.size()]];
          if (a == v || b == v || a == h || b == h) continue;
          if (segments_meet(h, v, a, b)) return false;
        }
        return true;
      };
      if (!clear_of(ring)) return false;
      for (std::size_t j = k; j < pending.size(); ++j)
        if (!clear_of(pending[j])) return false;
      return true;
    };
    int best = -1;
    double best_distance = INFINITY;
    const std::size_t n = ring.size();
    for (std::size_t s = 0; s < n; ++s) {
      const int_point& v = points[ring[s]];
      if (v == h) continue;
      const double distance = std::hypot(double(v.x - h.x), double(v.y - h.y));
      if (distance >= best_distance) continue;
      if (!inside_wedge(points[ring[(s + n - 1) % n]], v, points[ring[(s + 1) % n]], h)) continue;
      if (!bridge_is_clear(v)) continue;
      best = int(s);
      best_distance = distance;
    }
    if (best < 0) return {};  // no bridge: not a valid polygon with holes
    std::vector<int> merged(ring.begin(), ring.begin() + best + 1);
    for (std::size_t i = 0; i <= hole.size(); ++i) merged.push_back(hole[(start + i) % hole.size()]);
    merged.push_back(ring[best]);
    merged.insert(merged.end(), ring.begin() + best + 1, ring.end());
    ring = std::move(merged);
  }

  // Ear clipping on the ring, taking the best-shaped ear each time (the
  // largest smallest angle; the first ear found on large rings, where the
  // search would cost too much).
  const int n = int(ring.size());
  std::vector<int> prev(n), next(n);
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  auto is_ear = [&](int i) {
    const int_point &a = points[ring[prev[i]]], &b = points[ring[i]], &c = points[ring[next[i]]];
    if (orient(a, b, c) <= 0) return false;
    for (int k = next[next[i]]; k != prev[i]; k = next[k]) {
      const int_point& p = points[ring[k]];
      if (p == a || p == c) continue;
      if (p == b) {
        // The other copy of a bridge end: its edges must stay out of the ear.
        for (int q : {prev[k], next[k]}) {
          const int_point& r = points[ring[q]];
          if (r == a || r == c) continue;
          if (orient(a, b, r) > 0 && orient(b, c, r) > 0) return false;  // leaves b into the ear
        }
        continue;
      }
      if (orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0) return false;
    }
    return true;
  };
  std::vector<std::array<int, 3>> triangles;
  int left = n, cursor = 0;
  while (left > 3) {
    int chosen = -1;
    double chosen_quality = -1.0;
    int i = cursor;
    for (int step = 0; step < left; ++step, i = next[i]) {
      if (!is_ear(i)) continue;
      const double quality = smallest_angle(points[ring[prev[i]]], points[ring[i]], points[ring[next[i]]]);
      if (quality > chosen_quality) {
        chosen = i;
        chosen_quality = quality;
      }
      if (left > 256) break;
    }
    if (chosen < 0) {
      // No ear: only straight corners block (or the input is not simple).
      // Dropping a straight corner keeps the area; anything else fails.
      for (int step = 0; step < left; ++step, i = next[i])
        if (orient(points[ring[prev[i]]], points[ring[i]], points[ring[next[i]]]) == 0) {
          chosen = i;
          break;
        }
      if (chosen < 0) return {};
    } else {
      triangles.push_back({ring[prev[chosen]], ring[chosen], ring[next[chosen]]});
    }
    next[prev[chosen]] = next[chosen];
    prev[next[chosen]] = prev[chosen];
    cursor = next[chosen];
    --left;
  }
  if (left == 3 && orient(points[ring[prev[cursor]]], points[ring[cursor]], points[ring[next[cursor]]]) > 0)
    triangles.push_back({ring[prev[cursor]], ring[cursor], ring[next[cursor]]});
  return triangles;
}

namespace {

struct triangle_ref {
  int surface = 0;
  int triangle = 0;
  double offset = 0.0;  // along the group's normal
};

// Triangles of one plane: normal within coplanar_max_angle of `normal`,
// centroids within the tolerance of each other along it (chained).
struct plane_group {
  vec3 normal{0.0};
  std::vector<triangle_ref> triangles;
};

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
  std::map<std::tuple<long long, long long, long long>, std::vector<int>> cells;
  const double cos_max = std::cos(coplanar_max_angle);
  for (std::size_t s = 0; s < tessellated.size(); ++s) {
    if (!flat[s]) continue;
    const triangle_mesh& m = tessellated[s];
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const vec3 cross = triangle_cross(m, int(t));
      const double length = glm::length(cross);
      if (!(length > 0.0) || !std::isfinite(length)) continue;
      const vec3 n = cross / length;
      const auto cell = [&](const vec3& v) {
        return std::make_tuple(std::llround(v.x / coplanar_max_angle), std::llround(v.y / coplanar_max_angle),
                               std::llround(v.z / coplanar_max_angle));
      };
      const auto [cx, cy, cz] = cell(n);
      int found = -1;
      for (long long dx = -1; dx <= 1 && found < 0; ++dx)
        for (long long dy = -1; dy <= 1 && found < 0; ++dy)
          for (long long dz = -1; dz <= 1 && found < 0; ++dz) {
            auto it = cells.find({cx + dx, cy + dy, cz + dz});
            if (it == cells.end()) continue;
            for (int g : it->second)
              if (glm::dot(by_normal[g].normal, n) >= cos_max) {
                found = g;
                break;
              }
          }
      if (found < 0) {
        found = int(by_normal.size());
        by_normal.push_back({n, {}});
        cells[{cx, cy, cz}].push_back(found);
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

bool emitting(const material& m) {
  return m.ke.r > 0.0 || m.ke.g > 0.0 || m.ke.b > 0.0;
}

// One (surface, material) piece of a plane.
struct piece {
  int surface = 0;
  int material = 0;
  bool emits = false;
  double offset = 0.0;  // mean over its triangles
  std::vector<int> triangles;
};

// The plane's 2D integer frame: e1 x e2 = normal, so counter-clockwise in
// 2D is counter-clockwise seen from the front.
struct plane_frame {
  vec3 origin{0.0}, e1{0.0}, e2{0.0};
  double unit = 1.0;

  plane_frame(const vec3& normal, const vec3& centre, double extent) : origin(centre) {
    const vec3 a = std::abs(normal.x) < 0.6 ? vec3(1, 0, 0) : vec3(0, 1, 0);
    e1 = glm::normalize(glm::cross(a, normal));
    e2 = glm::cross(normal, e1);
    unit = std::max(extent, 1e-300) / double(1 << 29);  // |coordinates| <= 2^28
  }
  ClipperLib::IntPoint project(const vec3& p) const {
    return {std::llround(glm::dot(p - origin, e1) / unit), std::llround(glm::dot(p - origin, e2) / unit)};
  }
  vec2 plane_point(const ClipperLib::IntPoint& p) const { return {double(p.X) * unit, double(p.Y) * unit}; }
  vec2 exact(const vec3& p) const { return {glm::dot(p - origin, e1), glm::dot(p - origin, e2)}; }
};

ClipperLib::Paths piece_paths(const triangle_mesh& m, const std::vector<int>& triangles, const plane_frame& frame) {
  ClipperLib::Paths paths;
  for (int t : triangles) {
    ClipperLib::Path path;
    for (int k = 0; k < 3; ++k) path.push_back(frame.project(m.positions[m.triangles[t][k]]));
    if (ClipperLib::Area(path) > 0.0) paths.push_back(std::move(path));
  }
  return paths;
}

// Bounding boxes of the cover's triangles in a coarse grid, so that a
// piece that does not overlap the cover (most of them: surfaces that only
// share an edge, or lie apart in the same plane) skips the polygon
// clipping, which costs far more on large scenes.
class cover_boxes {
 public:
  void add(const ClipperLib::Paths& paths) {
    for (const ClipperLib::Path& path : paths) {
      const box b = bounds(path);
      const long long x0 = cell(b.x0), x1 = cell(b.x1), y0 = cell(b.y0), y1 = cell(b.y1);
      const int index = int(boxes_.size());
      boxes_.push_back(b);
      if ((x1 - x0 + 1) * (y1 - y0 + 1) > 64) {
        large_.push_back(index);
        continue;
      }
      for (long long x = x0; x <= x1; ++x)
        for (long long y = y0; y <= y1; ++y) cells_[{x, y}].push_back(index);
    }
  }
  // Whether some triangle of `paths` overlaps a cover triangle's box by
  // more than the rounding of the integer frame (touching does not count).
  bool may_overlap(const ClipperLib::Paths& paths) const {
    for (const ClipperLib::Path& path : paths) {
      const box b = bounds(path);
      for (int i : large_)
        if (overlap(b, boxes_[i])) return true;
      for (long long x = cell(b.x0); x <= cell(b.x1); ++x)
        for (long long y = cell(b.y0); y <= cell(b.y1); ++y) {
          auto it = cells_.find({x, y});
          if (it == cells_.end()) continue;
          for (int i : it->second)
            if (overlap(b, boxes_[i])) return true;
        }
    }
    return false;
  }

 private:
  struct box {
    long long x0, y0, x1, y1;
  };
  static box bounds(const ClipperLib::Path& path) {
    box b{path[0].X, path[0].Y, path[0].X, path[0].Y};
    for (const ClipperLib::IntPoint& q : path) {
      b.x0 = std::min(b.x0, q.X);
      b.y0 = std::min(b.y0, q.Y);
      b.x1 = std::max(b.x1, q.X);
      b.y1 = std::max(b.y1, q.Y);
    }
    return b;
  }
  static bool overlap(const box& a, const box& b) {
    constexpr long long slack = 4;  // integer units: rounding of shared corners
    return std::min(a.x1, b.x1) - std::max(a.x0, b.x0) > slack && std::min(a.y1, b.y1) - std::max(a.y0, b.y0) > slack;
  }
  static long long cell(long long v) { return v >> 21; }  // |v| <= 2^28: at most 256 cells a side
  std::vector<box> boxes_;
  std::vector<int> large_;
  std::map<std::pair<long long, long long>, std::vector<int>> cells_;
};

double tree_area(const ClipperLib::PolyTree& tree) {
  double area = 0.0;
  for (ClipperLib::PolyNode* node = tree.GetFirst(); node; node = node->GetNext())
    area += std::abs(ClipperLib::Area(node->Contour)) * (node->IsHole() ? -1.0 : 1.0);
  return area;
}

// Replaces piece p's triangles in this plane with a triangulation of
// `region`. False (nothing changed) if the region cannot be triangulated.
bool replace_piece(triangle_mesh& m, const piece& p, const ClipperLib::PolyTree& region, const plane_frame& frame,
                   const std::map<std::pair<long long, long long>, vec2>& cover_corners, std::vector<bool>& removed) {
  auto to_points = [](const ClipperLib::Path& path, bool counter_clockwise) {
    std::vector<int_point> out;
    for (const ClipperLib::IntPoint& q : path) out.push_back({q.X, q.Y});
    if ((ClipperLib::Area(path) > 0.0) != counter_clockwise) std::reverse(out.begin(), out.end());
    return out;
  };
  std::vector<std::array<int_point, 3>> added;
  for (ClipperLib::PolyNode* node = region.GetFirst(); node; node = node->GetNext()) {
    if (node->IsHole() || node->Contour.size() < 3) continue;
    std::vector<int_point> all = to_points(node->Contour, true);
    std::vector<std::vector<int_point>> holes;
    for (ClipperLib::PolyNode* child : node->Childs)
      if (child->Contour.size() >= 3) holes.push_back(to_points(child->Contour, false));
    const std::vector<std::array<int, 3>> triangles = triangulate_with_holes(all, holes);
    if (triangles.empty()) return false;
    for (const auto& h : holes) all.insert(all.end(), h.begin(), h.end());
    for (const auto& t : triangles) added.push_back({all[t[0]], all[t[1]], all[t[2]]});
  }

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
  auto vertex_at = [&](const int_point& q) {
    const auto [it, fresh] = made.try_emplace({q.x, q.y}, int(m.positions.size()));
    if (!fresh) return it->second;
    if (auto c = corners.find({q.x, q.y}); c != corners.end()) return it->second = c->second;
    // A corner of the cover (the light's) is placed where it is exactly,
    // not on the integer grid (which is 2^-29 of the scene's extent).
    const auto exact = cover_corners.find({q.x, q.y});
    const vec2 x = exact != cover_corners.end() ? exact->second : frame.plane_point({q.x, q.y});
    int best = p.triangles.front();
    double best_depth = -INFINITY;
    vec3 best_weights(1.0, 0.0, 0.0);
    for (int t : p.triangles) {
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
  for (const auto& t : added) {
    const glm::ivec3 tri(vertex_at(t[0]), vertex_at(t[1]), vertex_at(t[2]));
    m.triangles.push_back(tri);
    m.materials.push_back(p.material);
    removed.push_back(false);
  }
  return true;
}

}  // namespace

coplanar_cut_stats cut_coplanar_overlaps(std::vector<triangle_mesh>& tessellated, const std::vector<bool>& flat,
                                         const std::vector<material>& materials, double scene_diagonal) {
  coplanar_cut_stats stats;
  const double tolerance = coplanar_relative_tolerance * scene_diagonal;
  // The flat surfaces' extent, for the integer frames.
  vec3 lo(INFINITY), hi(-INFINITY);
  for (std::size_t s = 0; s < tessellated.size(); ++s)
    if (flat[s])
      for (const vec3& p : tessellated[s].positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
      }
  if (!(lo.x <= hi.x)) return stats;
  const vec3 centre = 0.5 * (lo + hi);
  const double extent = glm::length(hi - lo);

  std::vector<std::vector<bool>> removed(tessellated.size());
  for (std::size_t s = 0; s < tessellated.size(); ++s) removed[s].assign(tessellated[s].triangles.size(), false);
  for (const plane_group& plane : plane_groups(tessellated, flat, tolerance)) {
    std::map<std::pair<int, int>, piece> by_piece;
    for (const triangle_ref& r : plane.triangles) {
      const int mat = tessellated[r.surface].materials[r.triangle];
      piece& p = by_piece[{r.surface, mat}];
      p.surface = r.surface;
      p.material = mat;
      p.emits = mat >= 0 && std::size_t(mat) < materials.size() && emitting(materials[mat]);
      p.offset += r.offset;
      p.triangles.push_back(r.triangle);
    }
    if (by_piece.size() < 2) continue;
    std::vector<piece> pieces;
    for (auto& [key, p] : by_piece) {
      p.offset /= double(p.triangles.size());
      pieces.push_back(std::move(p));
    }
    // Highest rank first: emitters, then the front, then the later surface.
    std::sort(pieces.begin(), pieces.end(), [](const piece& a, const piece& b) {
      return std::tie(a.emits, a.offset, a.surface, a.material) > std::tie(b.emits, b.offset, b.surface, b.material);
    });
    const plane_frame frame(plane.normal, centre, extent);
    ClipperLib::Paths cover;
    cover_boxes cover_index;
    std::map<std::pair<long long, long long>, vec2> cover_corners;
    for (const piece& p : pieces) {
      triangle_mesh& m = tessellated[p.surface];
      const ClipperLib::Paths own = piece_paths(m, p.triangles, frame);
      if (!cover.empty() && !own.empty() && cover_index.may_overlap(own)) {
        ClipperLib::Clipper whole, cut;
        whole.PreserveCollinear(true);
        whole.AddPaths(own, ClipperLib::ptSubject, true);
        ClipperLib::PolyTree before, after;
        whole.Execute(ClipperLib::ctUnion, before, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
        cut.PreserveCollinear(true);
        cut.StrictlySimple(true);
        cut.AddPaths(own, ClipperLib::ptSubject, true);
        cut.AddPaths(cover, ClipperLib::ptClip, true);
        cut.Execute(ClipperLib::ctDifference, after, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
        const double area_before = tree_area(before), area_after = tree_area(after);
        // Only touching the cover (shared edges) leaves the area as it was.
        if (area_before - area_after > 1e-9 * area_before) {
          double old_area = 0.0, new_area = 0.0;
          for (int t : p.triangles) old_area += 0.5 * glm::length(triangle_cross(m, t));
          const std::size_t first_new = m.triangles.size();
          if (replace_piece(m, p, after, frame, cover_corners, removed[p.surface])) {
            for (std::size_t t = first_new; t < m.triangles.size(); ++t)
              new_area += 0.5 * glm::length(triangle_cross(m, int(t)));
            ++stats.surfaces_cut;
            stats.area_removed += old_area - new_area;
          } else {
            ++stats.pieces_left_uncut;  // the overlap stays: said, not hidden
          }
        }
      }
      cover.insert(cover.end(), own.begin(), own.end());
      cover_index.add(own);
      for (int t : p.triangles)
        for (int k = 0; k < 3; ++k) {
          const vec3& corner = m.positions[m.triangles[t][k]];
          const ClipperLib::IntPoint q = frame.project(corner);
          cover_corners.try_emplace({q.X, q.Y}, frame.exact(corner));
        }
    }
  }
  // Drop the replaced triangles.
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
  return stats;
}

}  // namespace bounce
