// Shadow outlines cut into the receiving planes (shadow_outlines.h).
#include "mesh/shadow_outlines.h"

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <numeric>
#include <unordered_map>

#include <clipper.hpp>
#include <glm/geometric.hpp>

#include "base/random_stream.h"
#include "image/tonemap.h"
#include "mesh/coplanar_cut.h"
#include "mesh/plane_pieces.h"
#include "scene/lights.h"

namespace bounce {
namespace {

// A light as the shadows see it: its corners (none for a light that is not
// outlined: point lights, curved lamps), the way it faces, and its power
// for the choice of lights.
struct light_shape {
  std::vector<vec3> corners;
  vec3 normal{0.0};
  double power = 0.0;
  double width = 0.0;  // the longest distance between two corners
};

// A convex occluder: its distinct corners and its triangles' edges (for
// the crossings with a receiving plane).
struct occluder {
  std::vector<vec3> corners;
  std::vector<std::array<vec3, 2>> edges;
};

struct box3 {
  vec3 lo{INFINITY}, hi{-INFINITY};
  void add(const vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool meets(const box3& o) const {
    return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y && lo.z <= o.hi.z && o.lo.z <= hi.z;
  }
};

// Convex hull of 2D points (Andrew's monotone chain), counter-clockwise.
std::vector<vec2> hull_2d(std::vector<vec2> p) {
  std::sort(p.begin(), p.end(), [](const vec2& a, const vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  auto cross = [](const vec2& o, const vec2& a, const vec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0.0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0.0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

// Positions as hash keys, bit for bit.
struct position_hash {
  std::size_t operator()(const std::array<double, 3>& p) const {
    std::uint64_t h = 0;
    for (double v : p) h = murmur_mix64(h ^ std::bit_cast<std::uint64_t>(v + 0.0));  // +0.0: -0 and 0 alike
    return std::size_t(h);
  }
};
using position_map = std::unordered_map<std::array<double, 3>, int, position_hash>;

// Connected parts of a triangle mesh, corners welded by position.
std::vector<std::vector<int>> connected_triangles(const triangle_mesh& m) {
  std::vector<int> parent(m.positions.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[std::size_t(x)] != x) x = parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
    return x;
  };
  position_map first_at;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const vec3& p = m.positions[v];
    const auto [it, fresh] = first_at.try_emplace({p.x, p.y, p.z}, int(v));
    if (!fresh) parent[std::size_t(find(int(v)))] = find(it->second);
  }
  for (const glm::ivec3& t : m.triangles) {
    parent[std::size_t(find(t[1]))] = find(t[0]);
    parent[std::size_t(find(t[2]))] = find(t[0]);
  }
  std::unordered_map<int, std::size_t> part_of;
  std::vector<std::vector<int>> parts;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto [it, fresh] = part_of.try_emplace(find(m.triangles[t][0]), parts.size());
    if (fresh) parts.emplace_back();
    parts[it->second].push_back(int(t));
  }
  return parts;
}

// Parts with more corners than this are not taken as occluders (the test
// of convexity is quadratic): a finely tessellated sphere, a whole room.
constexpr std::size_t max_occluder_corners = 512;

// The part as an occluder, if it is convex: all its corners on one side of
// the plane of each of its faces, and a flat part as large as its hull.
bool convex_occluder(const triangle_mesh& m, const std::vector<int>& part, double tolerance, occluder& out) {
  position_map seen;
  for (int t : part)
    for (int k = 0; k < 3; ++k) {
      const vec3& p = m.positions[m.triangles[t][k]];
      if (seen.try_emplace({p.x, p.y, p.z}, 0).second) out.corners.push_back(p);
      if (out.corners.size() > max_occluder_corners) return false;
    }
  bool flat = true;
  double area = 0.0;
  vec3 first_normal{0.0}, first_point{0.0};
  for (int t : part) {
    const glm::ivec3 tri = m.triangles[t];
    const vec3 cross = triangle_cross(m, t);
    const double length = glm::length(cross);
    if (!(length > 0.0)) continue;
    area += 0.5 * length;
    const vec3 n = cross / length;
    if (first_normal == vec3(0.0)) {
      first_normal = n;
      first_point = m.positions[tri[0]];
    }
    // One side of every face (either side: a shadow does not depend on
    // which way the faces were wound).
    bool behind = true, in_front = true;
    for (const vec3& c : out.corners) {
      const double h = glm::dot(n, c - m.positions[tri[0]]);
      behind = behind && h <= tolerance;
      in_front = in_front && h >= -tolerance;
      if (std::abs(glm::dot(first_normal, c - first_point)) > tolerance) flat = false;
    }
    if (!behind && !in_front) return false;
    for (int k = 0; k < 3; ++k) out.edges.push_back({m.positions[tri[k]], m.positions[tri[(k + 1) % 3]]});
  }
  if (first_normal == vec3(0.0)) return false;
  if (flat) {
    const plane_frame in_plane(first_normal, first_point, 1.0);
    std::vector<vec2> p;
    for (const vec3& c : out.corners) p.push_back(in_plane.exact(c));
    const std::vector<vec2> h = hull_2d(p);
    double hull_area = 0.0;
    for (std::size_t i = 0; i < h.size(); ++i) {
      const vec2 &a = h[i], &b = h[(i + 1) % h.size()];
      hull_area += 0.5 * (a.x * b.y - a.y * b.x);
    }
    if (std::abs(hull_area - area) > 1e-6 * hull_area) return false;  // an L-shaped panel, a flat ring
  }
  return true;
}

// The strong lights: the fewest, strongest first, that carry the power
// share, if at most shadow_outline_max_lights do; else none. Curved lamps
// and point lights among them are left out.
// parts_of(s): surface s's connected parts.
std::vector<light_shape> strong_lights(const std::vector<triangle_mesh>& tessellated, const std::vector<bool>& flat,
                                       const std::vector<material>& materials,
                                       const std::vector<punctual_light>& points, double scene_diagonal,
                                       auto&& parts_of) {
  std::vector<light_shape> all;
  // A punctual light's shadow edge is a jump in radiance, not in its slope:
  // a vertex on it would need a value for each side. Punctual lights count
  // in the power (a sun's: what reaches the scene's ball) but are not
  // outlined (they keep no corners).
  for (const punctual_light& l : points)
    all.push_back({{}, vec3(0.0), luminance(emitted_power(l, 0.5 * scene_diagonal)), 0.0});
  for (std::size_t s = 0; s < tessellated.size(); ++s) {
    const triangle_mesh& m = tessellated[s];
    const bool has_emitter = std::any_of(m.materials.begin(), m.materials.end(), [&](int mat) {
      return mat >= 0 && std::size_t(mat) < materials.size() && emitting(materials[std::size_t(mat)]);
    });
    if (!has_emitter) continue;
    for (const std::vector<int>& part : parts_of(s)) {
      // One light per connected emitting part of one material.
      std::map<int, std::vector<int>> by_material;
      for (int t : part) {
        const int mat = m.materials[std::size_t(t)];
        if (mat >= 0 && std::size_t(mat) < materials.size() && emitting(materials[std::size_t(mat)]))
          by_material[mat].push_back(t);
      }
      for (const auto& [mat, triangles] : by_material) {
        light_shape light;
        vec3 normal_sum(0.0);
        double area = 0.0;
        std::vector<vec3> corners;
        for (int t : triangles) {
          const vec3 cross = triangle_cross(m, t);
          normal_sum += cross;
          area += 0.5 * glm::length(cross);
          for (int k = 0; k < 3; ++k) corners.push_back(m.positions[m.triangles[std::size_t(t)][k]]);
        }
        light.power = std::numbers::pi * luminance(materials[std::size_t(mat)].ke) * area;
        // A curved lamp counts in the power, but its shadows are not
        // outlined (it keeps no corners).
        if (flat[s] && glm::length(normal_sum) > 0.0) {
          light.normal = glm::normalize(normal_sum);
          const plane_frame in_plane(light.normal, corners.front(), 1.0);
          std::vector<vec2> p;
          for (const vec3& c : corners) p.push_back(in_plane.exact(c));
          for (const vec2& q : hull_2d(p)) light.corners.push_back(in_plane.point(q));
          if (light.corners.size() < 3) light.corners.clear();
          for (const vec3& a : light.corners)
            for (const vec3& b : light.corners) light.width = std::max(light.width, glm::length(a - b));
        }
        all.push_back(std::move(light));
      }
    }
  }
  std::sort(all.begin(), all.end(), [](const light_shape& a, const light_shape& b) { return a.power > b.power; });
  double total = 0.0;
  for (const light_shape& l : all) total += l.power;
  double carried = 0.0;
  std::size_t count = 0;
  while (count < all.size() && count < shadow_outline_max_lights && carried < shadow_outline_power_share * total)
    carried += all[count++].power;
  if (!(total > 0.0) || carried < shadow_outline_power_share * total) return {};
  all.resize(count);
  std::erase_if(all, [](const light_shape& l) { return l.corners.empty(); });
  return all;
}

// Where a ray from `from` through `through` leaves the box.
vec3 exit_point(const vec3& from, const vec3& through, const box3& box) {
  const vec3 d = through - from;
  double t_exit = INFINITY;
  for (int a = 0; a < 3; ++a) {
    if (d[a] > 0.0) t_exit = std::min(t_exit, (box.hi[a] - from[a]) / d[a]);
    if (d[a] < 0.0) t_exit = std::min(t_exit, (box.lo[a] - from[a]) / d[a]);
  }
  if (!std::isfinite(t_exit)) return through;
  return from + std::max(t_exit, 1.0) * d;
}

// The region a light's shadow of an occluder can reach within the scene's
// box, or an empty box if the occluder is not wholly in front of the light.
box3 shadow_reach(const light_shape& light, const occluder& o, const box3& scene_box, double tolerance) {
  box3 reach;
  for (const vec3& e : light.corners)
    for (const vec3& c : o.corners) {
      if (glm::dot(light.normal, c - light.corners.front()) <= tolerance) return box3{};
      if (glm::length(c - e) <= tolerance) return box3{};
      reach.add(c);
      reach.add(exit_point(e, c, scene_box));
    }
  return reach;
}

ClipperLib::Path integer_ring(const std::vector<vec2>& ring, const plane_frame& frame) {
  ClipperLib::Path path;
  for (const vec2& q : ring) path.push_back(frame.integer(q));
  if (ClipperLib::Area(path) < 0.0) std::reverse(path.begin(), path.end());
  return path;
}

ClipperLib::Paths clip(ClipperLib::ClipType type, const ClipperLib::Paths& subject, const ClipperLib::Paths& by) {
  ClipperLib::Clipper c;
  c.PreserveCollinear(true);
  c.AddPaths(subject, ClipperLib::ptSubject, true);
  if (!by.empty()) c.AddPaths(by, ClipperLib::ptClip, true);
  ClipperLib::Paths out;
  c.Execute(type, out, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  return out;
}

// The penumbra and umbra of one occluder on the plane, in its integer
// frame: false if the occluder casts nothing there that can be outlined.
bool shadow_on_plane(const light_shape& light, const occluder& o, const vec3& n, double offset, double tolerance,
                     const plane_frame& frame, ClipperLib::Path& penumbra, ClipperLib::Paths& umbra,
                     double element_edge) {
  auto height = [&](const vec3& p) { return glm::dot(n, p) - offset; };
  double lowest_light = INFINITY;
  for (const vec3& e : light.corners) lowest_light = std::min(lowest_light, height(e));
  if (!(lowest_light > tolerance)) return false;
  // The occluder's part in front of the plane: its corners there and where
  // its edges cross the plane.
  std::vector<vec3> front;
  bool above = false;
  for (const vec3& c : o.corners) {
    const double h = height(c);
    if (h >= lowest_light - tolerance) return false;  // reaches the light's height: rays go up past it
    if (h >= -tolerance) front.push_back(c);
    above = above || h > tolerance;
  }
  if (!above) return false;
  // Smooth at the mesh's scale: a penumbra wider than an element (the
  // light is large for its distance) is followed by the solver's own
  // refinement; the outline would only add elements.
  double widest_penumbra = 0.0;
  for (const vec3& c : front) {
    const double h = std::max(height(c), 0.0);
    widest_penumbra = std::max(widest_penumbra, light.width * h / (lowest_light - h));
  }
  if (widest_penumbra > element_edge) return false;
  for (const auto& [a, b] : o.edges) {
    const double ha = height(a), hb = height(b);
    if ((ha < -tolerance && hb > tolerance) || (hb < -tolerance && ha > tolerance))
      front.push_back(a + (b - a) * (ha / (ha - hb)));
  }
  std::vector<vec2> all;
  std::vector<std::vector<vec2>> from_corner;
  for (const vec3& e : light.corners) {
    const double he = height(e);
    std::vector<vec2> projected;
    for (const vec3& c : front) {
      const double hc = std::max(height(c), 0.0);
      projected.push_back(frame.exact(e + (c - e) * (he / (he - hc))));
    }
    all.insert(all.end(), projected.begin(), projected.end());
    from_corner.push_back(hull_2d(std::move(projected)));
  }
  const std::vector<vec2> outer = hull_2d(std::move(all));
  if (outer.size() < 3) return false;
  vec2 lo(INFINITY), hi(-INFINITY);
  for (const vec2& q : outer) {
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  if (glm::length(hi - lo) < shadow_outline_smallest * element_edge) return false;
  penumbra = integer_ring(outer, frame);
  umbra.clear();
  if (from_corner.front().size() < 3) return true;
  umbra.push_back(integer_ring(from_corner.front(), frame));
  for (std::size_t i = 1; i < from_corner.size() && !umbra.empty(); ++i) {
    if (from_corner[i].size() < 3) return true;
    umbra = clip(ClipperLib::ctIntersection, umbra, {integer_ring(from_corner[i], frame)});
  }
  return true;
}

// Rings of a region as polygons with holes, in the triangulator's points.
struct polygon_with_holes {
  std::vector<int_point> outer;
  std::vector<std::vector<int_point>> holes;
};

void add_polygons(const ClipperLib::PolyTree& tree, std::vector<polygon_with_holes>& out) {
  auto to_points = [](const ClipperLib::Path& path, bool counter_clockwise) {
    std::vector<int_point> ring;
    for (const ClipperLib::IntPoint& q : path) ring.push_back({q.X, q.Y});
    if ((ClipperLib::Area(path) > 0.0) != counter_clockwise) std::reverse(ring.begin(), ring.end());
    return ring;
  };
  for (ClipperLib::PolyNode* node = tree.GetFirst(); node; node = node->GetNext()) {
    if (node->IsHole() || node->Contour.size() < 3) continue;
    polygon_with_holes p;
    p.outer = to_points(node->Contour, true);
    for (ClipperLib::PolyNode* child : node->Childs)
      if (child->Contour.size() >= 3) p.holes.push_back(to_points(child->Contour, false));
    out.push_back(std::move(p));
  }
}

// Points of one region that lie inside an edge of another (the three
// regions are cut apart by separate booleans) are put into that edge, so
// the regions' triangles meet corner to corner.
void close_t_junctions(std::vector<polygon_with_holes>& polygons) {
  std::vector<int_point> points;
  for (const polygon_with_holes& p : polygons) {
    points.insert(points.end(), p.outer.begin(), p.outer.end());
    for (const auto& h : p.holes) points.insert(points.end(), h.begin(), h.end());
  }
  const auto by_x = [](const int_point& a, const int_point& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); };
  std::sort(points.begin(), points.end(), by_x);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  auto fix = [&](std::vector<int_point>& ring) {
    std::vector<int_point> out;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const int_point a = ring[i], b = ring[(i + 1) % ring.size()];
      out.push_back(a);
      const long long x0 = std::min(a.x, b.x), x1 = std::max(a.x, b.x);
      std::vector<std::pair<double, int_point>> inside;
      auto it = std::lower_bound(points.begin(), points.end(), int_point{x0, LLONG_MIN}, by_x);
      for (; it != points.end() && it->x <= x1; ++it) {
        const int_point p = *it;
        if (p == a || p == b || p.y < std::min(a.y, b.y) || p.y > std::max(a.y, b.y)) continue;
        if ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x) != 0) continue;
        const double along = double(p.x - a.x) * double(b.x - a.x) + double(p.y - a.y) * double(b.y - a.y);
        inside.push_back({along, p});
      }
      std::sort(inside.begin(), inside.end(), [](const auto& u, const auto& v) { return u.first < v.first; });
      for (const auto& [along, p] : inside) out.push_back(p);
    }
    ring = std::move(out);
  };
  for (polygon_with_holes& p : polygons) {
    fix(p.outer);
    for (auto& h : p.holes) fix(h);
  }
}

// Rings in a coarse grid of their boxes, for those near a triangle.
class ring_index {
 public:
  explicit ring_index(ClipperLib::Paths rings) : rings_(std::move(rings)) {
    for (std::size_t i = 0; i < rings_.size(); ++i) {
      const ClipperLib::IntRect b = box_of(rings_[i]);
      boxes_.push_back(b);
      if ((cell(b.right) - cell(b.left) + 1) * (cell(b.bottom) - cell(b.top) + 1) > 64) {
        large_.push_back(int(i));
        continue;
      }
      for (long long x = cell(b.left); x <= cell(b.right); ++x)
        for (long long y = cell(b.top); y <= cell(b.bottom); ++y) cells_[{x, y}].push_back(int(i));
    }
    stamp_.assign(rings_.size(), 0);
  }
  // The rings whose boxes meet `box`. A hole comes with its outer ring
  // (whose box holds the hole's), so the rings, filled by positive winding,
  // are the region near the box.
  ClipperLib::Paths near(const ClipperLib::IntRect& box) {
    ClipperLib::Paths out;
    ++query_;
    auto take = [&](int i) {
      const ClipperLib::IntRect& b = boxes_[std::size_t(i)];
      if (b.left <= box.right && box.left <= b.right && b.top <= box.bottom && box.top <= b.bottom)
        out.push_back(rings_[std::size_t(i)]);
    };
    for (int i : large_) take(i);
    for (long long x = cell(box.left); x <= cell(box.right); ++x)
      for (long long y = cell(box.top); y <= cell(box.bottom); ++y) {
        const auto it = cells_.find({x, y});
        if (it == cells_.end()) continue;
        for (int i : it->second) {
          if (stamp_[std::size_t(i)] == query_) continue;
          stamp_[std::size_t(i)] = query_;
          take(i);
        }
      }
    return out;
  }

 private:
  static long long cell(long long v) { return v >> 22; }  // |v| <= 2^28: at most 128 cells a side
  ClipperLib::Paths rings_;
  std::vector<ClipperLib::IntRect> boxes_;
  std::vector<int> large_;  // over more than 64 cells: looked at by every query
  std::map<std::pair<long long, long long>, std::vector<int>> cells_;
  std::vector<unsigned> stamp_;
  unsigned query_ = 0;
};

// A plane's shadows united: the umbrae, the penumbrae less the umbrae, and
// the penumbrae (whose outside is lit). United once per plane, so only the
// outer boundaries stay and each triangle clips against finished regions.
struct plane_regions {
  ring_index umbra, half, penumbra;
  plane_regions(const ClipperLib::Paths& penumbrae, const ClipperLib::Paths& umbrae)
      : umbra(clip(ClipperLib::ctUnion, umbrae, {})),
        half(clip(ClipperLib::ctDifference, penumbrae, umbrae)),
        penumbra(clip(ClipperLib::ctUnion, penumbrae, {})) {}
};

double doubled_area(const int_point& a, const int_point& b, const int_point& c) {
  return double(b.x - a.x) * double(c.y - a.y) - double(b.y - a.y) * double(c.x - a.x);
}

// Splits triangle `own` into umbra, penumbra and lit regions (the rings
// near it, filled by positive winding) and triangulates them into `added`.
// False if the outlines do not cross it, or a region cannot be
// triangulated (`failed` then set).
bool split_triangle(const ClipperLib::Path& own, const ClipperLib::Paths& umb, const ClipperLib::Paths& half,
                    const ClipperLib::Paths& pen, std::vector<std::array<int_point, 3>>& added, bool& failed) {
  const double whole = std::abs(ClipperLib::Area(own));
  std::vector<polygon_with_holes> polygons;
  auto region = [&](ClipperLib::ClipType type, const ClipperLib::Paths& by) {
    if (by.empty() && type == ClipperLib::ctIntersection) return 0.0;
    ClipperLib::Clipper c;
    c.PreserveCollinear(true);
    c.StrictlySimple(true);
    c.AddPath(own, ClipperLib::ptSubject, true);
    if (!by.empty()) c.AddPaths(by, ClipperLib::ptClip, true);
    ClipperLib::PolyTree tree;
    c.Execute(type, tree, ClipperLib::pftNonZero, ClipperLib::pftPositive);
    add_polygons(tree, polygons);
    return tree_area(tree);
  };
  const double shaded = region(ClipperLib::ctIntersection, umb);
  const double penumbral = region(ClipperLib::ctIntersection, half);
  const double lit = region(ClipperLib::ctDifference, pen);
  // Crossed only if no region is the whole triangle.
  if (std::max({shaded, penumbral, lit}) >= whole * (1.0 - 1e-9)) return false;
  close_t_junctions(polygons);
  const std::size_t before = added.size();
  double covered = 0.0;
  for (const polygon_with_holes& p : polygons) {
    const std::vector<std::array<int, 3>> triangles = triangulate_with_holes(p.outer, p.holes);
    if (triangles.empty()) {
      added.resize(before);
      failed = true;
      return false;
    }
    std::vector<int_point> all = p.outer;
    for (const auto& h : p.holes) all.insert(all.end(), h.begin(), h.end());
    for (const auto& t : triangles) {
      added.push_back({all[std::size_t(t[0])], all[std::size_t(t[1])], all[std::size_t(t[2])]});
      covered += 0.5 * doubled_area(all[std::size_t(t[0])], all[std::size_t(t[1])], all[std::size_t(t[2])]);
    }
  }
  // The regions must tile the triangle (rounding of crossings aside).
  if (std::abs(covered - whole) > 1e-6 * whole) {
    added.resize(before);
    failed = true;
    return false;
  }
  return true;
}

}  // namespace

shadow_outline_stats cut_shadow_outlines(std::vector<triangle_mesh>& tessellated, const std::vector<bool>& flat,
                                         const std::vector<material>& materials,
                                         const std::vector<punctual_light>& lights, double scene_diagonal,
                                         double element_edge) {
  shadow_outline_stats stats;
  // Each surface's connected parts, found once (for the lights, then for
  // the occluders) and only if some light is strong.
  std::vector<std::vector<std::vector<int>>> parts(tessellated.size());
  std::vector<bool> parted(tessellated.size(), false);
  auto parts_of = [&](std::size_t s) -> const std::vector<std::vector<int>>& {
    if (!parted[s]) {
      parts[s] = connected_triangles(tessellated[s]);
      parted[s] = true;
    }
    return parts[s];
  };
  const std::vector<light_shape> strong = strong_lights(tessellated, flat, materials, lights, scene_diagonal, parts_of);
  if (strong.empty()) return stats;
  stats.lights = strong.size();
  const double tolerance = coplanar_relative_tolerance * scene_diagonal;
  box3 scene_box;
  for (const triangle_mesh& m : tessellated)
    for (const vec3& p : m.positions) scene_box.add(p);
  for (const light_shape& l : strong)
    for (const vec3& e : l.corners) scene_box.add(e);
  const vec3 centre = 0.5 * (scene_box.lo + scene_box.hi);
  const double extent = glm::length(scene_box.hi - scene_box.lo);

  // Occluders: convex parts that emit nothing.
  std::vector<occluder> occluders;
  for (std::size_t s = 0; s < tessellated.size(); ++s) {
    const triangle_mesh& m = tessellated[s];
    for (const std::vector<int>& part : parts_of(s)) {
      bool emits = false;
      for (int t : part) {
        const int mat = m.materials[std::size_t(t)];
        emits = emits || (mat >= 0 && std::size_t(mat) < materials.size() && emitting(materials[std::size_t(mat)]));
      }
      occluder o;
      if (!emits && convex_occluder(m, part, 1e-6 * scene_diagonal, o)) occluders.push_back(std::move(o));
    }
  }
  // Each (light, occluder) shadow's reach, for the planes it may fall on.
  struct reach {
    std::size_t light = 0, occluder = 0;
    box3 box;
  };
  std::vector<reach> reaches;
  for (std::size_t l = 0; l < strong.size(); ++l)
    for (std::size_t o = 0; o < occluders.size(); ++o) {
      const box3 b = shadow_reach(strong[l], occluders[o], scene_box, tolerance);
      if (b.lo.x <= b.hi.x) reaches.push_back({l, o, b});
    }
  if (reaches.empty()) return stats;

  std::vector<std::vector<bool>> removed(tessellated.size());
  for (std::size_t s = 0; s < tessellated.size(); ++s) removed[s].assign(tessellated[s].triangles.size(), false);
  for (const plane_group& plane : plane_groups(tessellated, flat, coplanar_relative_tolerance * scene_diagonal)) {
    box3 box;
    double offset = 0.0;
    std::size_t receiving = 0;
    for (const triangle_ref& r : plane.triangles) {
      const triangle_mesh& m = tessellated[std::size_t(r.surface)];
      const int mat = m.materials[std::size_t(r.triangle)];
      if (mat >= 0 && std::size_t(mat) < materials.size() && emitting(materials[std::size_t(mat)])) continue;
      for (int k = 0; k < 3; ++k) box.add(m.positions[m.triangles[std::size_t(r.triangle)][k]]);
      offset += r.offset;
      ++receiving;
    }
    if (receiving == 0 || glm::length(box.hi - box.lo) < shadow_outline_smallest * element_edge) continue;
    offset /= double(receiving);
    const plane_frame frame(plane.normal, centre, extent);
    ClipperLib::Paths penumbrae, umbrae;
    for (const reach& r : reaches) {
      if (!r.box.meets(box)) continue;
      ClipperLib::Path penumbra;
      ClipperLib::Paths umbra;
      if (!shadow_on_plane(strong[r.light], occluders[r.occluder], plane.normal, offset, tolerance, frame, penumbra,
                           umbra, element_edge))
        continue;
      penumbrae.push_back(std::move(penumbra));
      umbrae.insert(umbrae.end(), umbra.begin(), umbra.end());
      ++stats.shadows;
    }
    if (penumbrae.empty()) continue;
    plane_regions regions(penumbrae, umbrae);
    std::map<std::pair<int, int>, piece> by_piece;
    for (const triangle_ref& r : plane.triangles) {
      const int mat = tessellated[std::size_t(r.surface)].materials[std::size_t(r.triangle)];
      if (mat >= 0 && std::size_t(mat) < materials.size() && emitting(materials[std::size_t(mat)])) continue;
      piece& p = by_piece[{r.surface, mat}];
      p.surface = r.surface;
      p.material = mat;
      p.triangles.push_back(r.triangle);
    }
    for (auto& [key, p] : by_piece) {
      triangle_mesh& m = tessellated[std::size_t(p.surface)];
      piece crossed = p;
      crossed.triangles.clear();
      std::vector<std::array<int_point, 3>> added;
      std::vector<int> origins;
      for (int t : p.triangles) {
        const ClipperLib::Paths own = piece_paths(m, {t}, frame);
        if (own.empty()) continue;
        const ClipperLib::IntRect box = box_of(own[0]);
        const ClipperLib::Paths pen = regions.penumbra.near(box);
        if (pen.empty()) continue;
        bool failed = false;
        const std::size_t before = added.size();
        if (split_triangle(own[0], regions.umbra.near(box), regions.half.near(box), pen, added, failed)) {
          crossed.triangles.push_back(t);
          ++stats.triangles_split;
          stats.triangles_added += added.size() - before;
          origins.resize(added.size(), t);
        } else if (failed) {
          ++stats.triangles_left;
        }
      }
      if (!crossed.triangles.empty())
        replace_with(m, crossed, added, frame, {}, removed[std::size_t(p.surface)], &origins);
    }
  }
  drop_removed(tessellated, removed);
  return stats;
}

}  // namespace bounce
