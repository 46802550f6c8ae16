// Polygons with holes triangulated on integer points (polygon_triangulation.h):
// ear clipping with the holes bridged in, then Lawson's flips, every
// orientation test exact.
#include "mesh/polygon_triangulation.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <utility>

#include <glm/geometric.hpp>

#include "base/math_types.h"

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

}  // namespace bounce
