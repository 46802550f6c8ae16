// Coplanar overlaps cut out of the surface behind (coplanar_cut.h). The
// polygon boolean is Clipper's (Debian's libpolyclipping, integer
// coordinates); the triangulation of what is left is ear clipping with the
// holes bridged in, on the same integers, so every orientation test is exact.
#include "mesh/coplanar_cut.h"

#include "base/random_stream.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>

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

// Whether d lies strictly inside the circle through a, b, c (counter-
// clockwise). Exact: coordinates within +-2^29.
bool in_circle(const int_point& a, const int_point& b, const int_point& c, const int_point& d) {
  const __int128 adx = a.x - d.x, ady = a.y - d.y, bdx = b.x - d.x, bdy = b.y - d.y, cdx = c.x - d.x, cdy = c.y - d.y;
  const __int128 det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) -
                       (bdx * bdx + bdy * bdy) * (adx * cdy - cdx * ady) +
                       (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
  return det > 0;
}

// Lawson's flips: an edge that is not constrained, between two triangles
// whose union is convex, is flipped while the far corner of one lies in
// the other's circumcircle. Ear clipping alone leaves slivers, which
// longest-edge bisection keeps (it halves angles at worst).
void make_delaunay(const std::vector<int_point>& points, const std::set<std::pair<int, int>>& constrained,
                   std::vector<std::array<int, 3>>& triangles) {
  std::map<std::pair<int, int>, std::vector<int>> by_edge;  // undirected edge -> triangles
  auto key = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  auto link = [&](int t) {
    for (int k = 0; k < 3; ++k) by_edge[key(triangles[t][k], triangles[t][(k + 1) % 3])].push_back(t);
  };
  auto unlink = [&](int t) {
    for (int k = 0; k < 3; ++k) {
      auto& list = by_edge[key(triangles[t][k], triangles[t][(k + 1) % 3])];
      list.erase(std::remove(list.begin(), list.end(), t), list.end());
    }
  };
  for (int t = 0; t < int(triangles.size()); ++t) link(t);
  std::vector<std::pair<int, int>> stack;
  for (const auto& [edge, list] : by_edge) stack.push_back(edge);
  std::size_t budget = 64 * triangles.size() * triangles.size() + 64;
  while (!stack.empty() && budget-- > 0) {
    const std::pair<int, int> edge = stack.back();
    stack.pop_back();
    if (constrained.count(edge)) continue;
    const auto it = by_edge.find(edge);
    if (it == by_edge.end() || it->second.size() != 2) continue;
    const int t1 = it->second[0], t2 = it->second[1];
    // t1 = (a, b, c) with edge a -> b; t2 has b -> a and its third corner d.
    int a = -1, b = -1, c = -1, d = -1;
    for (int k = 0; k < 3; ++k) {
      const int p = triangles[t1][k], q = triangles[t1][(k + 1) % 3];
      if (key(p, q) == edge) {
        a = p;
        b = q;
        c = triangles[t1][(k + 2) % 3];
      }
    }
    for (int k = 0; k < 3; ++k)
      if (triangles[t2][k] != a && triangles[t2][k] != b) d = triangles[t2][k];
    if (a < 0 || d < 0 || c == d) continue;
    const int_point &pa = points[a], &pb = points[b], &pc = points[c], &pd = points[d];
    if (!in_circle(pa, pb, pc, pd)) continue;
    if (orient(pa, pd, pc) <= 0 || orient(pd, pb, pc) <= 0) continue;  // not convex: no flip
    unlink(t1);
    unlink(t2);
    triangles[t1] = {a, d, c};
    triangles[t2] = {d, b, c};
    link(t1);
    link(t2);
    for (const auto& e : {key(a, d), key(d, b), key(b, c), key(c, a)}) stack.push_back(e);
  }
}

// A ring's corners in a uniform grid of about one corner per cell, for the
// corners inside an ear: testing every corner made ear clipping cubic on a
// floor triangle with two thousand holes.
class corner_grid {
 public:
  corner_grid(const std::vector<int_point>& points, const std::vector<int>& ring) : alive_(ring.size(), true) {
    lo_ = hi_ = points[std::size_t(ring[0])];
    for (int r : ring) {
      const int_point& p = points[std::size_t(r)];
      lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y)};
      hi_ = {std::max(hi_.x, p.x), std::max(hi_.y, p.y)};
    }
    const double width = double(hi_.x - lo_.x) + 1.0, height = double(hi_.y - lo_.y) + 1.0;
    const double side = std::max(std::sqrt(width * height / double(ring.size())), 1.0);
    columns_ = int(std::clamp(std::ceil(width / side), 1.0, 4096.0));
    rows_ = int(std::clamp(std::ceil(height / side), 1.0, 4096.0));
    start_.assign(std::size_t(columns_) * std::size_t(rows_) + 1, 0);
    for (int r : ring) ++start_[cell(points[std::size_t(r)]) + 1];
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    nodes_.resize(ring.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t node = 0; node < ring.size(); ++node)
      nodes_[fill[cell(points[std::size_t(ring[node])])]++] = int(node);
  }
  void remove(int node) { alive_[std::size_t(node)] = false; }
  // Calls visit(node) for every live node whose corner may lie in [a, b].
  template <class Visit>
  bool all_of(const int_point& a, const int_point& b, Visit&& visit) const {
    const int x0 = column(a.x), x1 = column(b.x), y0 = row(a.y), y1 = row(b.y);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const std::size_t c = std::size_t(y) * std::size_t(columns_) + std::size_t(x);
        for (std::size_t at = start_[c]; at < start_[c + 1]; ++at)
          if (alive_[std::size_t(nodes_[at])] && !visit(nodes_[at])) return false;
      }
    return true;
  }

 private:
  int column(long long x) const {
    return std::clamp(int(double(x - lo_.x) * double(columns_) / (double(hi_.x - lo_.x) + 1.0)), 0, columns_ - 1);
  }
  int row(long long y) const {
    return std::clamp(int(double(y - lo_.y) * double(rows_) / (double(hi_.y - lo_.y) + 1.0)), 0, rows_ - 1);
  }
  std::size_t cell(const int_point& p) const {
    return std::size_t(row(p.y)) * std::size_t(columns_) + std::size_t(column(p.x));
  }
  int_point lo_, hi_;
  int columns_ = 1, rows_ = 1;
  std::vector<std::size_t> start_;  // by cell: where its nodes begin (one past the last cell: the end)
  std::vector<int> nodes_;
  std::vector<bool> alive_;
};

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
    // The nearest corner whose bridge is clear: corners by distance, so
    // that a floor with many holes costs a few checks per hole.
    int best = -1;
    const std::size_t n = ring.size();
    std::vector<std::pair<double, int>> by_distance;
    by_distance.reserve(n);
    for (std::size_t s = 0; s < n; ++s) {
      const int_point& v = points[ring[s]];
      if (v == h) continue;
      if (!inside_wedge(points[ring[(s + n - 1) % n]], v, points[ring[(s + 1) % n]], h)) continue;
      const double dx = double(v.x - h.x), dy = double(v.y - h.y);
      by_distance.emplace_back(dx * dx + dy * dy, int(s));
    }
    // A heap, not a sort: the first or second corner is nearly always clear.
    const auto farther = [](const std::pair<double, int>& a, const std::pair<double, int>& b) { return b < a; };
    std::make_heap(by_distance.begin(), by_distance.end(), farther);
    for (auto end = by_distance.end(); end != by_distance.begin(); --end) {
      std::pop_heap(by_distance.begin(), end, farther);
      const int s = (end - 1)->second;
      if (bridge_is_clear(points[ring[std::size_t(s)]])) {
        best = s;
        break;
      }
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
  // search would cost too much). The flips below settle the shapes, but
  // where corners are cocircular (a rectangle's) the ears decide.
  const int n = int(ring.size());
  std::vector<int> prev(n), next(n);
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  corner_grid grid(points, ring);
  auto is_ear = [&](int i) {
    const int_point &a = points[ring[prev[i]]], &b = points[ring[i]], &c = points[ring[next[i]]];
    if (orient(a, b, c) <= 0) return false;
    const int_point lo{std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y})};
    const int_point hi{std::max({a.x, b.x, c.x}), std::max({a.y, b.y, c.y})};
    return grid.all_of(lo, hi, [&](int k) {
      if (k == i || k == prev[i] || k == next[i]) return true;
      const int_point& p = points[ring[k]];
      if (p == a || p == c) return true;
      if (p == b) {
        // The other copy of a bridge end: its edges must stay out of the ear.
        for (int q : {prev[k], next[k]}) {
          const int_point& r = points[ring[q]];
          if (r == a || r == c) continue;
          if (orient(a, b, r) > 0 && orient(b, c, r) > 0) return false;  // leaves b into the ear
        }
        return true;
      }
      return !(orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0);
    });
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
    grid.remove(chosen);
    cursor = next[chosen];
    --left;
  }
  if (left == 3 && orient(points[ring[prev[cursor]]], points[ring[cursor]], points[ring[next[cursor]]]) > 0)
    triangles.push_back({ring[prev[cursor]], ring[cursor], ring[next[cursor]]});
  // The polygon's and the holes' edges are kept; every other edge is
  // flipped until the triangulation is constrained Delaunay.
  std::set<std::pair<int, int>> constrained;
  auto constrain = [&](int a, int b) { constrained.insert({std::min(a, b), std::max(a, b)}); };
  for (std::size_t i = 0; i < outer.size(); ++i) constrain(int(i), int((i + 1) % outer.size()));
  for (const std::vector<int>& hole : pending)
    for (std::size_t i = 0; i < hole.size(); ++i) constrain(hole[i], hole[(i + 1) % hole.size()]);
  make_delaunay(points, constrained, triangles);
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
    const ClipperLib::IntRect r = box_of(path);
    return {r.left, r.top, r.right, r.bottom};
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
                  std::vector<bool>& removed) {
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
  drop_removed(tessellated, removed);
  return stats;
}

namespace {

// Distance along d from o to triangle (a, b, c) (Moller-Trumbore), or
// infinity; `front` is whether d meets its front.
double ray_hit(const vec3& o, const vec3& d, const vec3& a, const vec3& b, const vec3& c, bool& front) {
  const vec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-300) return INFINITY;
  const vec3 t = o - a;
  const double u = glm::dot(t, p) / det;
  if (u < 0.0 || u > 1.0) return INFINITY;
  const vec3 q = glm::cross(t, e1);
  const double v = glm::dot(d, q) / det;
  if (v < 0.0 || u + v > 1.0) return INFINITY;
  const double distance = glm::dot(e2, q) / det;
  front = det > 0.0;  // d runs against the counter-clockwise normal
  return distance > 0.0 ? distance : INFINITY;
}

// Every triangle of the scene in a uniform grid of its bounding boxes, for
// the triangles near a plane and those above a point. The cells are one
// dense table (offsets into one id list): a hash map's lookups, a cache miss
// each, cost more than all else when a floor's slab spans a building.
class triangle_grid {
 public:
  triangle_grid(const std::vector<triangle_mesh>& tessellated, const vec3& lo, const vec3& hi) : lo_(lo) {
    std::size_t count = 0;
    for (const triangle_mesh& m : tessellated) count += m.triangles.size();
    const vec3 size = glm::max(hi - lo, vec3(1e-300));
    // Four times the cube root of the triangle count along the largest
    // side (furnished rooms are dense, and a plane's slab should meet few),
    // with no more cells than four per triangle over the whole box.
    const double largest = std::max({size.x, size.y, size.z});
    double cells = std::clamp(4.0 * std::cbrt(double(count)), 1.0, 512.0);
    cell_ = largest / cells;
    const double budget = 4.0 * double(std::max<std::size_t>(count, 1));
    auto total_cells = [&] {
      double total = 1.0;
      for (int k = 0; k < 3; ++k) total *= std::max(1.0, std::ceil(size[k] / cell_));
      return total;
    };
    while (total_cells() > budget && cells > 1.0) {
      cells = std::max(1.0, cells * 0.8);
      cell_ = largest / cells;
    }
    for (int k = 0; k < 3; ++k) dims_[k] = std::max(1, int(std::ceil(size[k] / cell_)));
    std::vector<std::pair<glm::ivec3, glm::ivec3>> spans;
    for (std::size_t s = 0; s < tessellated.size(); ++s) {
      const triangle_mesh& m = tessellated[s];
      for (std::size_t t = 0; t < m.triangles.size(); ++t) {
        vec3 a(INFINITY), b(-INFINITY);
        for (int k = 0; k < 3; ++k) {
          a = glm::min(a, m.positions[m.triangles[t][k]]);
          b = glm::max(b, m.positions[m.triangles[t][k]]);
        }
        refs_.emplace_back(int(s), int(t));
        spans.emplace_back(cell_of(a), cell_of(b));
      }
    }
    // Counted, then filled: a flat layer of cells across the grid is fine;
    // a solid block of them is not, and goes to the list every query takes.
    start_.assign(std::size_t(dims_[0]) * dims_[1] * dims_[2] + 1, 0);
    auto each_cell = [&](std::size_t id, auto&& visit) {
      const auto& [c0, c1] = spans[id];
      const long long span = (long long)(c1.x - c0.x + 1) * (c1.y - c0.y + 1) * (c1.z - c0.z + 1);
      if (span > (1 << 20)) return false;
      for (int x = c0.x; x <= c1.x; ++x)
        for (int y = c0.y; y <= c1.y; ++y)
          for (int z = c0.z; z <= c1.z; ++z) visit(key(x, y, z));
      return true;
    };
    for (std::size_t id = 0; id < refs_.size(); ++id)
      if (!each_cell(id, [&](std::size_t cell) { ++start_[cell + 1]; })) large_.push_back(int(id));
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    ids_.resize(start_.back());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t id = 0; id < refs_.size(); ++id)
      each_cell(id, [&](std::size_t cell) { ids_[fill[cell]++] = int(id); });
    stamp_.assign(refs_.size(), 0);
  }

  // The triangles (surface, triangle) whose boxes may meet box [a, b],
  // each once.
  std::vector<std::pair<int, int>> near(const vec3& a, const vec3& b) const {
    ++query_;
    std::vector<std::pair<int, int>> out;
    auto take = [&](int id) {
      if (stamp_[std::size_t(id)] == query_) return;
      stamp_[std::size_t(id)] = query_;
      out.push_back(refs_[std::size_t(id)]);
    };
    for (int id : large_) take(id);
    const glm::ivec3 c0 = cell_of(a), c1 = cell_of(b);
    for (int x = c0.x; x <= c1.x; ++x)
      for (int y = c0.y; y <= c1.y; ++y)
        for (int z = c0.z; z <= c1.z; ++z)
          for (std::size_t at = start_[key(x, y, z)]; at < start_[key(x, y, z) + 1]; ++at) take(ids_[at]);
    return out;
  }

  // The nearest triangle along the ray from o in unit direction d: its
  // distance (infinity if none) and whether the ray meets its front
  // (faces within `tolerance` of the nearest count as one, behind winning).
  // Walks the cells the ray passes (Amanatides & Woo), stopping past a hit.
  double first_hit(const std::vector<triangle_mesh>& tessellated, const vec3& o, const vec3& d, double tolerance,
                   bool& front) const {
    ++query_;
    double nearest = INFINITY;
    front = true;
    auto test = [&](int id) {
      if (stamp_[std::size_t(id)] == query_) return;
      stamp_[std::size_t(id)] = query_;
      const auto [surface, t] = refs_[std::size_t(id)];
      const triangle_mesh& m = tessellated[std::size_t(surface)];
      const glm::ivec3 tri = m.triangles[std::size_t(t)];
      bool faces = true;
      const double distance = ray_hit(o, d, m.positions[tri[0]], m.positions[tri[1]], m.positions[tri[2]], faces);
      if (distance < nearest - tolerance) {
        nearest = distance;
        front = faces;
      } else if (distance < nearest + tolerance) {
        nearest = std::min(nearest, distance);
        front = front && faces;
      }
    };
    for (int id : large_) test(id);
    glm::ivec3 c = cell_of(o);
    glm::ivec3 step;
    vec3 t_max, t_delta;
    for (int k = 0; k < 3; ++k) {
      step[k] = d[k] > 0.0 ? 1 : (d[k] < 0.0 ? -1 : 0);
      const double boundary = lo_[k] + (c[k] + (step[k] > 0 ? 1 : 0)) * cell_;
      t_max[k] = step[k] != 0 ? (boundary - o[k]) / d[k] : INFINITY;
      t_delta[k] = step[k] != 0 ? cell_ / std::abs(d[k]) : INFINITY;
    }
    for (;;) {
      for (std::size_t at = start_[key(c.x, c.y, c.z)]; at < start_[key(c.x, c.y, c.z) + 1]; ++at) test(ids_[at]);
      const int k = t_max.x < t_max.y ? (t_max.x < t_max.z ? 0 : 2) : (t_max.y < t_max.z ? 1 : 2);
      if (nearest + tolerance < t_max[k]) break;  // nothing farther can be nearer
      c[k] += step[k];
      if (step[k] == 0 || c[k] < 0 || c[k] >= dims_[k]) break;
      t_max[k] += t_delta[k];
    }
    return nearest;
  }

 private:
  glm::ivec3 cell_of(const vec3& p) const {
    glm::ivec3 c;
    for (int k = 0; k < 3; ++k) c[k] = std::clamp(int(std::floor((p[k] - lo_[k]) / cell_)), 0, dims_[k] - 1);
    return c;
  }
  std::size_t key(int x, int y, int z) const {
    return (std::size_t(x) * std::size_t(dims_[1]) + std::size_t(y)) * std::size_t(dims_[2]) + std::size_t(z);
  }
  vec3 lo_;
  double cell_ = 1.0;
  int dims_[3] = {1, 1, 1};
  std::vector<std::pair<int, int>> refs_;  // by id: (surface, triangle)
  std::vector<std::size_t> start_;         // by cell: where its ids begin in ids_ (one past the last cell: the end)
  std::vector<int> ids_;
  std::vector<int> large_;
  mutable std::vector<unsigned> stamp_;  // per id: the last query that took it
  mutable unsigned query_ = 0;
};

// The point where edge (a, b) crosses height h along n (d: heights), the
// same bits from either triangle that shares the edge.
vec3 crossing(vec3 a, vec3 b, double da, double db, double h) {
  if (std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z)) {
    std::swap(a, b);
    std::swap(da, db);
  }
  return a + (b - a) * ((h - da) / (db - da));
}

// A plane's triangles in pieces that touch (share a corner): the table
// tops of a building at one height are one plane but many parts, each
// looked at over its own extent.
std::vector<plane_group> connected_parts(const std::vector<triangle_mesh>& tessellated, const plane_group& plane) {
  std::vector<int> parent(plane.triangles.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = int(i);
  auto find = [&](int i) {
    while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
    return i;
  };
  std::map<std::tuple<double, double, double>, int> first_at;
  for (std::size_t i = 0; i < plane.triangles.size(); ++i) {
    const triangle_mesh& m = tessellated[std::size_t(plane.triangles[i].surface)];
    for (int k = 0; k < 3; ++k) {
      const vec3& p = m.positions[m.triangles[std::size_t(plane.triangles[i].triangle)][k]];
      const auto [it, fresh] = first_at.try_emplace({p.x, p.y, p.z}, int(i));
      if (!fresh) parent[std::size_t(find(int(i)))] = find(it->second);
    }
  }
  std::map<int, std::size_t> part_of;
  std::vector<plane_group> out;
  for (std::size_t i = 0; i < plane.triangles.size(); ++i) {
    const auto [it, fresh] = part_of.try_emplace(find(int(i)), out.size());
    if (fresh) out.push_back({plane.normal, {}});
    out[it->second].triangles.push_back(plane.triangles[i]);
  }
  return out;
}

// One connected part of a plane, and the plane lifted above it that the
// search cuts with.
struct contact_part {
  const plane_group& plane;
  vec3 lo{INFINITY}, hi{-INFINITY};  // its box
  double front = -INFINITY;          // its offset along the normal
  double h = 0.0;                    // the lifted plane: normal . x = h
  plane_frame frame;

  contact_part(const std::vector<triangle_mesh>& tessellated, const plane_group& p, double lift, const vec3& centre,
               double extent)
      : plane(p), frame(p.normal, centre, extent) {
    for (const triangle_ref& r : plane.triangles) {
      const triangle_mesh& m = tessellated[std::size_t(r.surface)];
      front = std::max(front, r.offset);
      for (int k = 0; k < 3; ++k) {
        lo = glm::min(lo, m.positions[m.triangles[std::size_t(r.triangle)][k]]);
        hi = glm::max(hi, m.positions[m.triangles[std::size_t(r.triangle)][k]]);
      }
    }
    h = front + lift;
  }
  const vec3& normal() const { return plane.normal; }
  // A point of the plane's frame, at height `height` along the normal.
  vec3 point(const vec2& x, double height) const {
    return frame.origin + x.x * frame.e1 + x.y * frame.e2 + normal() * (height - glm::dot(normal(), frame.origin));
  }
};

// The triangles that cross the part's lifted plane within `reach` of its
// box (along an axis the plane faces, only the slab around it).
std::vector<std::pair<int, int>> crossing_near(const std::vector<triangle_mesh>& tessellated, const triangle_grid& grid,
                                               const contact_part& part, double lift, double reach) {
  const vec3& n = part.normal();
  vec3 query_lo = part.lo - vec3(reach), query_hi = part.hi + vec3(reach);
  for (int k = 0; k < 3; ++k)
    if (std::abs(n[k]) > 1.0 - 1e-9) query_lo[k] = query_hi[k] = part.h * n[k];
  query_lo -= vec3(lift);
  query_hi += vec3(lift);
  std::vector<std::pair<int, int>> out = grid.near(query_lo, query_hi);
  std::erase_if(out, [&](const std::pair<int, int>& ref) {
    const triangle_mesh& m = tessellated[std::size_t(ref.first)];
    const glm::ivec3 tri = m.triangles[std::size_t(ref.second)];
    double lo_d = INFINITY, hi_d = -INFINITY;
    vec3 lo_p(INFINITY), hi_p(-INFINITY);
    for (int k = 0; k < 3; ++k) {
      const double d = glm::dot(n, m.positions[tri[k]]);
      lo_d = std::min(lo_d, d);
      hi_d = std::max(hi_d, d);
      lo_p = glm::min(lo_p, m.positions[tri[k]]);
      hi_p = glm::max(hi_p, m.positions[tri[k]]);
    }
    const bool in_box = glm::all(glm::lessThanEqual(lo_p, query_hi)) && glm::all(glm::lessThanEqual(query_lo, hi_p));
    return !(lo_d < part.h && hi_d > part.h && in_box);
  });
  return out;
}

// Where crossing triangles meet the lifted plane: a directed segment each,
// with the solid's inside on its left seen from the front (outward-facing
// solids give counter-clockwise loops; a room's inward-facing walls,
// clockwise ones), and the exact plane positions of their integer ends.
struct crossing_segments {
  std::vector<std::array<ClipperLib::IntPoint, 2>> segments;
  std::multimap<std::pair<long long, long long>, std::size_t> starting;
  std::map<std::pair<long long, long long>, vec2> exact_points;
};

crossing_segments segments_of(const std::vector<triangle_mesh>& tessellated,
                              const std::vector<std::pair<int, int>>& triangles, const contact_part& part) {
  const vec3& n = part.normal();
  const double h = part.h;
  crossing_segments out;
  for (const auto& [surface, t] : triangles) {
    const triangle_mesh& m = tessellated[std::size_t(surface)];
    const glm::ivec3 tri = m.triangles[std::size_t(t)];
    double d[3];
    for (int k = 0; k < 3; ++k) d[k] = glm::dot(n, m.positions[tri[k]]);
    std::vector<vec3> points;
    for (int k = 0; k < 3; ++k) {
      const int j = (k + 1) % 3;
      if ((d[k] >= h) != (d[j] >= h))
        points.push_back(crossing(m.positions[tri[k]], m.positions[tri[j]], d[k], d[j], h));
    }
    if (points.size() != 2) continue;
    const vec3 along = glm::cross(n, triangle_cross(m, t));
    if (glm::dot(points[1] - points[0], along) < 0.0) std::swap(points[0], points[1]);
    const ClipperLib::IntPoint p0 = part.frame.project(points[0]), p1 = part.frame.project(points[1]);
    if (p0 == p1) continue;
    out.exact_points.try_emplace({p0.X, p0.Y}, part.frame.exact(points[0]));
    out.exact_points.try_emplace({p1.X, p1.Y}, part.frame.exact(points[1]));
    out.starting.emplace(std::make_pair(p0.X, p0.Y), out.segments.size());
    out.segments.push_back({p0, p1});
  }
  return out;
}

// The segments chained into loops: the closed counter-clockwise ones, and
// whether a chain stayed open over `part_box` (a solid on the part reaching
// past the search; chains open only outside it, such as a wall beside the
// part, are not).
struct chained_loops {
  ClipperLib::Paths closed;
  bool open_over_part = false;
};

chained_loops closed_loops(const crossing_segments& s, const ClipperLib::IntRect& part_box) {
  const auto& segments = s.segments;
  chained_loops out;
  std::vector<bool> used(segments.size(), false);
  for (std::size_t first = 0; first < segments.size(); ++first) {
    if (used[first]) continue;
    ClipperLib::Path loop;
    std::size_t at = first;
    bool closed = false;
    while (true) {
      used[at] = true;
      loop.push_back(segments[at][0]);
      const ClipperLib::IntPoint end = segments[at][1];
      if (end == segments[first][0]) {
        closed = true;
        break;
      }
      // Where solids touch, several segments leave one point: the one
      // turning most to the left keeps to the boundary of one solid, the
      // same whatever order the segments came in.
      std::size_t next = segments.size();
      double best_turn = -INFINITY;
      const double in_x = double(end.X - segments[at][0].X), in_y = double(end.Y - segments[at][0].Y);
      for (auto [it, stop] = s.starting.equal_range({end.X, end.Y}); it != stop; ++it) {
        if (used[it->second]) continue;
        const double out_x = double(segments[it->second][1].X - end.X),
                     out_y = double(segments[it->second][1].Y - end.Y);
        const double turn = std::atan2(in_x * out_y - in_y * out_x, in_x * out_x + in_y * out_y);
        if (turn > best_turn || (turn == best_turn && it->second < next)) {
          best_turn = turn;
          next = it->second;
        }
      }
      if (next == segments.size()) break;
      at = next;
    }
    if (!closed) {
      for (const ClipperLib::IntPoint& q : loop)
        if (q.X > part_box.left && q.X < part_box.right && q.Y > part_box.top && q.Y < part_box.bottom)
          out.open_over_part = true;
      continue;
    }
    // A quad face split by a diagonal crosses the plane twice along one
    // line: the point in between goes (it would leave slivers). Straight
    // means within 2 integer units of the line through the neighbours.
    for (std::size_t i = 0; loop.size() > 3 && i < loop.size();) {
      const ClipperLib::IntPoint& p = loop[(i + loop.size() - 1) % loop.size()];
      const ClipperLib::IntPoint& q = loop[(i + 1) % loop.size()];
      const double dx = double(q.X - p.X), dy = double(q.Y - p.Y);
      const double cross = dx * double(loop[i].Y - p.Y) - dy * double(loop[i].X - p.X);
      if (std::abs(cross) <= 2.0 * std::hypot(dx, dy))
        loop.erase(loop.begin() + std::ptrdiff_t(i));
      else
        ++i;
    }
    if (loop.size() >= 3 && ClipperLib::Area(loop) > 0.0) out.closed.push_back(std::move(loop));
  }
  return out;
}

// The part's box in its plane's integer frame.
ClipperLib::IntRect plane_box(const std::vector<triangle_mesh>& tessellated, const contact_part& part) {
  ClipperLib::Path corners;
  for (const triangle_ref& r : part.plane.triangles) {
    const triangle_mesh& m = tessellated[std::size_t(r.surface)];
    for (int k = 0; k < 3; ++k)
      corners.push_back(part.frame.project(m.positions[m.triangles[std::size_t(r.triangle)][k]]));
  }
  return box_of(corners);
}

// Whether the inside of `loop` is closed above: straight up from a point
// inside it, the first face is met from behind (coincident faces count as
// behind). The region under a solid, which no light reaches and no eye sees.
bool closed_above(const std::vector<triangle_mesh>& tessellated, const triangle_grid& grid, const contact_part& part,
                  const ClipperLib::Path& loop, double tolerance) {
  std::vector<int_point> ring;
  for (const ClipperLib::IntPoint& q : loop) ring.push_back({q.X, q.Y});
  const std::vector<std::array<int, 3>> ears = triangulate_with_holes(ring, {});
  if (ears.empty()) return false;
  const vec2 inside =
      (part.frame.plane_point(loop[std::size_t(ears[0][0])]) + part.frame.plane_point(loop[std::size_t(ears[0][1])]) +
       part.frame.plane_point(loop[std::size_t(ears[0][2])])) /
      3.0;
  bool front = true;
  const double nearest = grid.first_hit(tessellated, part.point(inside, part.h), part.normal(), tolerance, front);
  return nearest != INFINITY && !front;
}

// Cuts `cover` out of the part's pieces, triangle by triangle with the
// loops over it: one polygon with thousands of holes (every room's floor
// under its furniture) would cost far more to triangulate. Returns whether
// anything was cut.
bool cut_part(std::vector<triangle_mesh>& tessellated, const contact_part& part, const ClipperLib::Paths& cover,
              const std::map<std::pair<long long, long long>, vec2>& exact_points,
              std::vector<std::vector<bool>>& removed, contact_cut_stats& stats) {
  bool cut_any = false;
  std::vector<ClipperLib::IntRect> loop_boxes;
  for (const ClipperLib::Path& loop : cover) loop_boxes.push_back(box_of(loop));
  // The loops' boxes in a grid of about one loop per cell.
  ClipperLib::IntRect all = loop_boxes[0];
  for (const ClipperLib::IntRect& r : loop_boxes) {
    all.left = std::min(all.left, r.left);
    all.top = std::min(all.top, r.top);
    all.right = std::max(all.right, r.right);
    all.bottom = std::max(all.bottom, r.bottom);
  }
  const double side = std::max<double>({double(all.right - all.left), double(all.bottom - all.top), 1.0}) /
                      std::max(1.0, std::sqrt(double(cover.size())));
  auto cell = [&](long long v, long long from) { return (long long)(std::floor(double(v - from) / side)); };
  std::unordered_map<long long, std::vector<int>> loop_cells;
  auto cell_key = [](long long x, long long y) { return (x << 32) ^ (y & 0xffffffffLL); };
  for (std::size_t l = 0; l < loop_boxes.size(); ++l)
    for (long long x = cell(loop_boxes[l].left, all.left); x <= cell(loop_boxes[l].right, all.left); ++x)
      for (long long y = cell(loop_boxes[l].top, all.top); y <= cell(loop_boxes[l].bottom, all.top); ++y)
        loop_cells[cell_key(x, y)].push_back(int(l));
  std::vector<unsigned> seen(cover.size(), 0);
  unsigned query = 0;
  std::map<std::pair<int, int>, piece> by_piece;
  for (const triangle_ref& r : part.plane.triangles) {
    piece& p = by_piece[{r.surface, tessellated[r.surface].materials[r.triangle]}];
    p.surface = r.surface;
    p.material = tessellated[r.surface].materials[r.triangle];
    p.triangles.push_back(r.triangle);
  }
  for (auto& [key, p] : by_piece) {
    triangle_mesh& m = tessellated[p.surface];
    piece affected = p;
    affected.triangles.clear();
    std::vector<std::array<int_point, 3>> added;
    double old_area = 0.0;
    for (int t : p.triangles) {
      const ClipperLib::Paths own = piece_paths(m, {t}, part.frame);
      if (own.empty()) continue;
      const ClipperLib::IntRect box = box_of(own[0]);
      ++query;
      ClipperLib::Paths over;
      for (long long x = std::max(cell(box.left, all.left), 0LL); x <= cell(box.right, all.left); ++x)
        for (long long y = std::max(cell(box.top, all.top), 0LL); y <= cell(box.bottom, all.top); ++y) {
          const auto it = loop_cells.find(cell_key(x, y));
          if (it == loop_cells.end()) continue;
          for (int l : it->second) {
            if (seen[std::size_t(l)] == query) continue;
            seen[std::size_t(l)] = query;
            const ClipperLib::IntRect& lb = loop_boxes[std::size_t(l)];
            if (lb.left < box.right && lb.right > box.left && lb.top < box.bottom && lb.bottom > box.top)
              over.push_back(cover[std::size_t(l)]);
          }
        }
      if (over.empty()) continue;
      ClipperLib::PolyTree after;
      ClipperLib::Clipper cut;
      auto difference = [&](bool strictly_simple) {
        cut.Clear();
        cut.PreserveCollinear(true);
        cut.StrictlySimple(strictly_simple);
        cut.AddPaths(own, ClipperLib::ptSubject, true);
        cut.AddPaths(over, ClipperLib::ptClip, true);
        cut.Execute(ClipperLib::ctDifference, after, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
      };
      // Not strictly simple: Clipper's fix-up of touching rings is
      // quadratic in their number; asked for only where the
      // triangulation of the difference fails.
      difference(false);
      const double area_before = std::abs(ClipperLib::Area(own[0])), area_after = tree_area(after);
      if (!(area_before - area_after > 1e-9 * area_before)) continue;
      if (area_after > 0.0 && !triangulate_region(after, added)) {
        difference(true);
        if (!triangulate_region(after, added)) {
          ++stats.pieces_left_uncut;
          continue;
        }
      }
      old_area += 0.5 * glm::length(triangle_cross(m, t));
      affected.triangles.push_back(t);  // wholly under solids: replaced by nothing
    }
    if (affected.triangles.empty()) continue;
    const std::size_t first_new = m.triangles.size();
    replace_with(m, affected, added, part.frame, exact_points, removed[p.surface]);
    double new_area = 0.0;
    for (std::size_t t = first_new; t < m.triangles.size(); ++t)
      new_area += 0.5 * glm::length(triangle_cross(m, int(t)));
    ++stats.pieces_cut;
    stats.area_removed += old_area - new_area;
    cut_any = true;
  }
  return cut_any;
}

// The loops' edges, in the part's plane: where solids stand on it.
void record_outline(const contact_part& part, const ClipperLib::Paths& cover,
                    const std::map<std::pair<long long, long long>, vec2>& exact_points, contact_cut_stats& stats) {
  for (const ClipperLib::Path& loop : cover)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      std::array<vec3, 2> edge;
      for (int k = 0; k < 2; ++k) {
        const ClipperLib::IntPoint& q = loop[(i + std::size_t(k)) % loop.size()];
        const auto exact = exact_points.find({q.X, q.Y});
        edge[std::size_t(k)] =
            part.point(exact != exact_points.end() ? exact->second : part.frame.plane_point(q), part.front);
      }
      stats.outline.push_back(edge);
    }
}

}  // namespace

contact_cut_stats cut_buried_contacts(std::vector<triangle_mesh>& tessellated, const std::vector<bool>& flat,
                                      double scene_diagonal, double smallest_part) {
  contact_cut_stats stats;
  const double tolerance = coplanar_relative_tolerance * scene_diagonal;
  const double lift = contact_lift * scene_diagonal;
  vec3 lo(INFINITY), hi(-INFINITY);
  for (const triangle_mesh& m : tessellated)
    for (const vec3& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  if (!(lo.x <= hi.x)) return stats;
  const vec3 centre = 0.5 * (lo + hi);
  const double extent = glm::length(hi - lo);
  const triangle_grid grid(tessellated, lo, hi);
  std::vector<std::vector<bool>> removed(tessellated.size());
  for (std::size_t s = 0; s < tessellated.size(); ++s) removed[s].assign(tessellated[s].triangles.size(), false);

  std::vector<plane_group> parts;
  for (const plane_group& whole : plane_groups(tessellated, flat, tolerance)) {
    std::vector<plane_group> split = connected_parts(tessellated, whole);
    parts.insert(parts.end(), std::make_move_iterator(split.begin()), std::make_move_iterator(split.end()));
  }
  for (const plane_group& plane : parts) {
    const contact_part part(tessellated, plane, lift, centre, extent);
    // A part smaller than a tenth of an element is a fraction of one: not
    // worth the search (furnished rooms have half a million of them).
    const double size = glm::length(part.hi - part.lo);
    if (size < smallest_part) continue;
    // Fewer than three triangles cross over the part itself: no loop
    // stands on it (most planes: the faces of furniture, which the floor
    // alone crosses).
    const std::vector<std::pair<int, int>> over_part = crossing_near(tessellated, grid, part, lift, 2.0 * lift);
    if (over_part.size() < 3) continue;
    crossing_segments segments = segments_of(tessellated, over_part, part);
    const ClipperLib::IntRect whole_box = plane_box(tessellated, part);
    const long long margin = std::llround(2.0 * lift / part.frame.unit);
    const ClipperLib::IntRect part_box{whole_box.left + margin, whole_box.top + margin, whole_box.right - margin,
                                       whole_box.bottom - margin};
    chained_loops loops = closed_loops(segments, part_box);
    // A chain that leaves the part: search again as far as the part
    // reaches. A solid that overhangs the part by more than that (a long
    // table top over its legs' tops) leaves an open chain, and cuts nothing
    // there. Most solids stand inside their part, and skip the wide search.
    if (loops.open_over_part && size > 2.0 * lift) {
      segments = segments_of(tessellated, crossing_near(tessellated, grid, part, lift, size), part);
      loops = closed_loops(segments, part_box);
    }
    // Loops off the part (a wide search meets its neighbours' solids) are
    // neither cut nor counted.
    ClipperLib::Paths cover;
    for (ClipperLib::Path& loop : loops.closed) {
      const ClipperLib::IntRect b = box_of(loop);
      const bool meets =
          b.left < whole_box.right && whole_box.left < b.right && b.top < whole_box.bottom && whole_box.top < b.bottom;
      if (meets && closed_above(tessellated, grid, part, loop, tolerance)) cover.push_back(std::move(loop));
    }
    if (cover.empty() || !cut_part(tessellated, part, cover, segments.exact_points, removed, stats)) continue;
    stats.footprints += cover.size();
    record_outline(part, cover, segments.exact_points, stats);
  }
  drop_removed(tessellated, removed);
  return stats;
}

}  // namespace bounce
