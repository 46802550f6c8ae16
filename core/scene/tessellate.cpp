// Turning a scene's surfaces into triangles: ear clipping for polygon faces,
// a longitude/latitude grid for spheres, marching tetrahedra for quadrics and
// parameter grids for Bezier and B-spline surfaces.
#include "scene/tessellate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <optional>
#include <unordered_map>
#include <utility>
#include <variant>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vector_relational.hpp>

#include "base/check.h"

namespace bounce {
namespace {

using std::numbers::pi;

// Sanity caps on resolution. They bound the work for absurd max_edge values
// (callers refuse those through estimate_triangles) and keep vertex indices
// inside int.
constexpr int max_sphere_segments = 1 << 14;  // around the equator
constexpr int max_patch_segments = 1 << 10;   // per Bezier patch or B-spline span, per direction
constexpr int max_quadric_cells_per_axis = 1 << 10;
constexpr double max_quadric_cells = 1 << 24;
// estimate_triangles counts a quadric's triangles on a grid at most this fine.
constexpr int estimate_cells_per_axis = 64;
// Grid cells across a bounded quadric's smallest extent, whatever max_edge
// says: fewer and a small sphere falls between the grid nodes.
constexpr int min_quadric_cells = 4;
// Quadric cells shrink for curvature at most this many times per axis, so
// that a cone's apex (curvature without bound) cannot ask for a grid
// without end.
constexpr double max_curvature_shrink = 6.0;
constexpr double radians_per_edge = curved_degrees_per_edge * std::numbers::pi / 180.0;

// ---------------------------------------------------------------------------
// Small helpers

// A non-negative count held in a double, as size_t, saturating.
std::size_t saturate(double n) {
  constexpr double top = static_cast<double>(std::numeric_limits<std::size_t>::max());
  if (!(n > 0.0)) return 0;
  if (n >= top) return std::numeric_limits<std::size_t>::max();
  return static_cast<std::size_t>(n);
}

// Segments of at most max_edge covering `length`, clamped to [lo, hi]. Works
// in double so that a tiny max_edge cannot overflow.
int segments_for(double length, double max_edge, int lo, int hi) {
  const double n = std::ceil(length / max_edge);
  if (!(n > lo)) return lo;  // also catches NaN
  return n < hi ? static_cast<int>(n) : hi;
}

vec3 unit_or_zero(const vec3& v) {
  const double len = glm::length(v);
  return len > 0.0 && std::isfinite(len) ? v / len : vec3(0.0);
}

int add_vertex(triangle_mesh& m, const vec3& p, const vec3& n, const vec2& uv) {
  BOUNCE_CHECK_LT(m.positions.size(), static_cast<std::size_t>(std::numeric_limits<int>::max()));
  m.positions.push_back(p);
  m.normals.push_back(n);
  m.uvs.push_back(uv);
  return static_cast<int>(m.positions.size() - 1);
}

void add_triangle(triangle_mesh& m, int a, int b, int c, int material) {
  m.triangles.emplace_back(a, b, c);
  m.materials.push_back(material);
}

// Twice the area times the unit normal of triangle (a, b, c).
vec3 triangle_cross(const triangle_mesh& m, int a, int b, int c) {
  return glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
}

// A triangle worth keeping: three distinct vertices and a non-zero area
// (a zero-area element would divide by zero downstream).
bool is_proper(const triangle_mesh& m, int a, int b, int c) {
  return a != b && b != c && a != c && triangle_cross(m, a, b, c) != vec3(0.0);
}

// Gives vertices without a normal (zero, e.g. at a cone's apex) the
// area-weighted mean normal of their triangles.
void fill_missing_normals(triangle_mesh& m) {
  const auto missing = [&](int v) { return m.normals[v] == vec3(0.0); };
  if (std::none_of(m.normals.begin(), m.normals.end(), [](const vec3& n) { return n == vec3(0.0); })) return;
  std::vector<vec3> sum(m.positions.size(), vec3(0.0));
  for (const glm::ivec3& t : m.triangles) {
    const vec3 n = triangle_cross(m, t.x, t.y, t.z);
    for (int i = 0; i < 3; ++i)
      if (missing(t[i])) sum[t[i]] += n;
  }
  for (std::size_t v = 0; v < sum.size(); ++v) {
    if (!missing(static_cast<int>(v))) continue;
    const vec3 n = unit_or_zero(sum[v]);
    m.normals[v] = n != vec3(0.0) ? n : vec3(0.0, 0.0, 1.0);
  }
}

// Drops triangles that are not proper and the vertices no triangle uses.
void remove_degenerate(triangle_mesh& m) {
  triangle_mesh out;
  std::vector<int> new_index(m.positions.size(), -1);
  const auto keep = [&](int v) {
    if (new_index[v] < 0) new_index[v] = add_vertex(out, m.positions[v], m.normals[v], m.uvs[v]);
    return new_index[v];
  };
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const glm::ivec3& tri = m.triangles[t];
    if (!is_proper(m, tri.x, tri.y, tri.z)) continue;
    const int a = keep(tri.x), b = keep(tri.y), c = keep(tri.z);
    add_triangle(out, a, b, c, m.materials[t]);
  }
  m = std::move(out);
}

// Merges the `candidates` vertices that lie within tol of each other into one
// (averaging their normals), then drops collapsed triangles. Used to join the
// patches of one smooth surface and to close poles where a patch edge
// collapses to a point.
void weld(triangle_mesh& m, std::vector<int> candidates, double tol) {
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  // Sweep in x order: only vertices within tol in x can merge.
  std::sort(candidates.begin(), candidates.end(), [&](int a, int b) { return m.positions[a].x < m.positions[b].x; });
  std::vector<int> target(m.positions.size());
  std::iota(target.begin(), target.end(), 0);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const int keep = candidates[i];
    if (target[keep] != keep) continue;
    for (std::size_t k = i + 1; k < candidates.size(); ++k) {
      const int other = candidates[k];
      if (m.positions[other].x - m.positions[keep].x > tol) break;
      if (target[other] == other && glm::distance(m.positions[other], m.positions[keep]) <= tol) target[other] = keep;
    }
  }
  std::vector<vec3> normal_sum = m.normals;
  for (std::size_t v = 0; v < target.size(); ++v)
    if (target[v] != static_cast<int>(v)) normal_sum[target[v]] += m.normals[v];
  for (std::size_t v = 0; v < target.size(); ++v) {
    const vec3 n = unit_or_zero(normal_sum[v]);
    if (n != vec3(0.0)) m.normals[v] = n;  // opposite normals cancel: keep the vertex's own
  }
  for (glm::ivec3& t : m.triangles) t = glm::ivec3(target[t.x], target[t.y], target[t.z]);
  remove_degenerate(m);
}

double bounding_diagonal(const std::vector<vec3>& points) {
  if (points.empty()) return 0.0;
  vec3 lo = points.front(), hi = points.front();
  for (const vec3& p : points) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return glm::distance(lo, hi);
}

// ---------------------------------------------------------------------------
// Polygon faces

struct corner {
  int position;
  int normal;  // -1: none given
  int uv;      // -1: none given
};

// The face's corners with consecutive repeats of a position removed,
// including the last against the first.
std::vector<corner> distinct_corners(const polygon_face& f) {
  BOUNCE_DCHECK(f.normal.empty() || f.normal.size() == f.position.size());
  BOUNCE_DCHECK(f.uv.empty() || f.uv.size() == f.position.size());
  std::vector<corner> out;
  for (std::size_t i = 0; i < f.position.size(); ++i) {
    const corner c{f.position[i], f.normal.empty() ? -1 : f.normal[i], f.uv.empty() ? -1 : f.uv[i]};
    if (out.empty() || out.back().position != c.position) out.push_back(c);
  }
  while (out.size() > 1 && out.back().position == out.front().position) out.pop_back();
  return out;
}

// Newell's normal: its length is twice the polygon's area, and the polygon
// is counter-clockwise seen from the side it points to. Taken relative to
// the first corner to keep precision far from the origin.
vec3 newell_normal(const std::vector<vec3>& p) {
  vec3 n(0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const vec3 a = p[i] - p[0];
    const vec3 b = p[(i + 1) % p.size()] - p[0];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

// Zero or negligible area compared with the square of the longest edge.
bool has_area(const std::vector<vec3>& p, const vec3& newell) {
  double longest = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const vec3 e = p[(i + 1) % p.size()] - p[i];
    longest = std::max(longest, glm::dot(e, e));
  }
  return 0.5 * glm::length(newell) > 1e-12 * longest;
}

// The polygon in 2D, dropping the normal's dominant axis, ordered so that it
// is counter-clockwise when seen from the side the normal points to.
std::vector<vec2> project_to_plane(const std::vector<vec3>& p, const vec3& normal) {
  const vec3 a = glm::abs(normal);
  const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  int i = (axis + 1) % 3, j = (axis + 2) % 3;
  if (normal[axis] < 0.0) std::swap(i, j);
  std::vector<vec2> out;
  out.reserve(p.size());
  for (const vec3& q : p) out.emplace_back(q[i], q[j]);
  return out;
}

// Twice the signed area of 2D triangle (a, b, c): positive when counter-clockwise.
double cross2(const vec2& a, const vec2& b, const vec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Ear clipping of a simple counter-clockwise polygon; triangles as corner
// indices, counter-clockwise. When rounding leaves no clean ear, the most
// convex corner goes (with its triangle, if that has area), so it always ends.
//
// The ring is a linked list and the search for the next ear resumes where
// the last one was cut, so a convex polygon costs O(n). Only reflex (or
// straight) corners can lie inside an ear of a simple polygon, so only they
// are tested against it: O(n r) for r reflex corners.
std::vector<glm::ivec3> ear_clip(const std::vector<vec2>& p) {
  const int n = static_cast<int>(p.size());
  std::vector<glm::ivec3> out;
  if (n < 3) return out;
  out.reserve(static_cast<std::size_t>(n) - 2);
  std::vector<int> prev(n), next(n);
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  std::vector<char> alive(n, 1), reflex(n, 0);
  std::vector<int> reflex_list;
  const auto corner_cross = [&](int v) { return cross2(p[prev[v]], p[v], p[next[v]]); };
  for (int i = 0; i < n; ++i)
    if (corner_cross(i) <= 0.0) {
      reflex[i] = 1;
      reflex_list.push_back(i);
    }
  std::size_t stale = 0;  // entries of reflex_list no longer reflex or alive

  // Whether a reflex corner other than the ear's own lies inside or on the
  // ear (a, b, c). Corners at the same place as the ear's are not in the way.
  const auto blocked = [&](int a, int b, int c) {
    if (stale > reflex_list.size() / 2) {
      std::erase_if(reflex_list, [&](int r) { return !alive[r] || !reflex[r]; });
      stale = 0;
    }
    for (int r : reflex_list) {
      if (!alive[r] || !reflex[r]) continue;
      const vec2& q = p[r];
      if (q == p[a] || q == p[b] || q == p[c]) continue;
      if (cross2(p[a], p[b], q) >= 0.0 && cross2(p[b], p[c], q) >= 0.0 && cross2(p[c], p[a], q) >= 0.0) return true;
    }
    return false;
  };
  const auto update = [&](int v) {
    const char now = corner_cross(v) <= 0.0;
    if (now == reflex[v]) return;
    if (now) {
      reflex_list.push_back(v);
    } else {
      ++stale;
    }
    reflex[v] = now;
  };
  const auto clip = [&](int b) {
    const int a = prev[b], c = next[b];
    if (cross2(p[a], p[b], p[c]) > 0.0) out.emplace_back(a, b, c);
    alive[b] = 0;
    if (reflex[b]) ++stale;
    next[a] = c;
    prev[c] = a;
    update(a);
    update(c);
  };

  int remaining = n, v = 0;
  while (remaining > 3) {
    // Walk the ring once from v: the first clean ear, else the most convex.
    int ear = -1, most_convex = v;
    double most_cross = -std::numeric_limits<double>::infinity();
    int k = v;
    for (int step = 0; step < remaining; ++step, k = next[k]) {
      const double cr = corner_cross(k);
      if (cr > most_cross) {
        most_cross = cr;
        most_convex = k;
      }
      if (cr > 0.0 && !blocked(prev[k], k, next[k])) {
        ear = k;
        break;
      }
    }
    const int cut = ear >= 0 ? ear : most_convex;
    v = next[cut];
    clip(cut);
    --remaining;
  }
  // The last three, starting from the lowest index.
  int first = v;
  for (int i = 0, k = v; i < 3; ++i, k = next[k]) first = std::min(first, k);
  const int a = first, b = next[a], c = next[b];
  if (cross2(p[a], p[b], p[c]) > 0.0) out.emplace_back(a, b, c);
  return out;
}

// ---------------------------------------------------------------------------
// Sphere: a longitude/latitude grid. Chosen over an icosphere because its
// (longitude, latitude) uv is the natural texture map and its rings make
// the pole fans simple; a single vertex per pole and per seam position keeps
// the mesh closed (so u jumps from (n-1)/n back to 0 across the seam).

struct sphere_grid {
  int around;  // segments around the polar (y) axis
  int rows;    // segments from pole to pole
};

sphere_grid sphere_resolution(const sphere& s, double max_edge) {
  const int turn = int(std::ceil(2.0 * pi / radians_per_edge - 1e-9));
  const int around = segments_for(2.0 * pi * s.radius, max_edge, turn, max_sphere_segments);
  return {around, std::max(4, (around + 1) / 2)};
}

double sphere_triangles(const sphere_grid& g) {
  return 2.0 * g.around * (g.rows - 1.0);
}

// ---------------------------------------------------------------------------
// Quadric: marching tetrahedra over a grid of cubes filling the box.

vec3 quadric_gradient_at(const quadric& q, const vec3& p) {
  return 2.0 * vec3(q.a * p.x + q.d * p.y + q.f * p.z + q.g,  //
                    q.d * p.x + q.b * p.y + q.e * p.z + q.h,  //
                    q.f * p.x + q.e * p.y + q.c * p.z + q.j);
}

// The quadratic part of the polynomial at direction d.
double quadric_form(const quadric& q, const vec3& d) {
  return q.a * d.x * d.x + q.b * d.y * d.y + q.c * d.z * d.z +
         2.0 * (q.d * d.x * d.y + q.e * d.y * d.z + q.f * d.x * d.z);
}

struct quadric_grid {
  vec3 lo, hi;
  glm::ivec3 cells;
};

// Cells per axis for cubes of edge `cell`, in double so nothing overflows.
vec3 cell_counts(const quadric& q, double cell) {
  return glm::max(glm::ceil((q.box_max - q.box_min) / cell), vec3(1.0));
}

double product(const vec3& v) {
  return v.x * v.y * v.z;
}

quadric_grid quadric_resolution(const quadric& q, double cell) {
  BOUNCE_CHECK(glm::all(glm::lessThan(q.box_min, q.box_max)));
  vec3 n = cell_counts(q, cell);
  if (product(n) > max_quadric_cells) {
    cell *= std::cbrt(product(n) / max_quadric_cells);
    n = cell_counts(q, cell);
    while (product(n) > max_quadric_cells) n = cell_counts(q, cell *= 1.01);  // ceil's leftovers
  }
  n = glm::min(n, vec3(max_quadric_cells_per_axis));
  return {q.box_min, q.box_max, glm::ivec3(n)};
}

vec3 node_position(const quadric_grid& g, int i, int j, int k) {
  return g.lo + (g.hi - g.lo) * vec3(i, j, k) / vec3(g.cells);
}

// A grid edge that the surface crosses, from its negative end to its other
// end (f >= 0). The key is the same in every cell that meets the edge, so
// neighbouring cells share the vertex; where f is exactly 0 at the far end
// the vertex is that grid node, keyed by the node.
struct crossing {
  std::int64_t key;
  vec3 neg, pos;
  double f_neg, f_pos;
};

// Corners of a cube: bit 0 is +x, bit 1 +y, bit 2 +z. The six tetrahedra
// around the 0-7 diagonal (Kuhn's split) cut every face the same way in
// neighbouring cubes, so together they form a conforming mesh.
constexpr int cube_tets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

struct cube {
  double f[8];
  vec3 p[8];
  std::int64_t node[8];
};

// The crossing on the edge from negative corner a to non-negative corner b.
// Kuhn edges join corners whose bit sets nest, so (a & b) is the edge's low
// end and (a ^ b) its direction, one of 7.
crossing make_crossing(const cube& c, int a, int b) {
  BOUNCE_DCHECK((a & b) == a || (a & b) == b);
  const std::int64_t key = c.f[b] == 0.0 ? c.node[b] * 8 + 7 : c.node[a & b] * 8 + (a ^ b) - 1;
  return {key, c.p[a], c.p[b], c.f[a], c.f[b]};
}

// Hands the surface's piece inside one tetrahedron to the sink, with the
// direction from its negative corners towards the others for orientation.
template <class Sink>
void march_tet(const cube& c, const int (&tet)[4], Sink& sink) {
  int neg[4], pos[4], nn = 0, np = 0;
  for (int v : tet) (c.f[v] < 0.0 ? neg[nn++] : pos[np++]) = v;
  if (nn == 0 || np == 0) return;
  vec3 side(0.0);
  for (int i = 0; i < np; ++i) side += c.p[pos[i]] / double(np);
  for (int i = 0; i < nn; ++i) side -= c.p[neg[i]] / double(nn);
  const auto x = [&](int a, int b) { return make_crossing(c, a, b); };
  if (nn == 1)
    sink.triangle(x(neg[0], pos[0]), x(neg[0], pos[1]), x(neg[0], pos[2]), side);
  else if (np == 1)
    sink.triangle(x(neg[0], pos[0]), x(neg[1], pos[0]), x(neg[2], pos[0]), side);
  else  // a quad, its corners in cyclic order
    sink.quad(x(neg[0], pos[0]), x(neg[0], pos[1]), x(neg[1], pos[1]), x(neg[1], pos[0]), side);
}

// Bound on the size of the polynomial's terms at p, for its rounding error.
double quadric_magnitude(const quadric& q, const vec3& p) {
  const vec3 a = glm::abs(p);
  return std::abs(q.a) * a.x * a.x + std::abs(q.b) * a.y * a.y + std::abs(q.c) * a.z * a.z +
         2.0 * (std::abs(q.d) * a.x * a.y + std::abs(q.e) * a.y * a.z + std::abs(q.f) * a.x * a.z +
                std::abs(q.g) * a.x + std::abs(q.h) * a.y + std::abs(q.j) * a.z) +
         std::abs(q.k);
}

// The polynomial at a grid node, exactly 0 where it is 0 up to rounding: the
// surface then passes through the node, which becomes the vertex. (Crossings
// a hair's breadth from a node would give zero-area triangles instead.)
double node_value(const quadric& q, const vec3& p) {
  const double f = quadric_value(q, p);
  return std::abs(f) <= 1e-10 * quadric_magnitude(q, p) ? 0.0 : f;
}

// Marches every cube of the grid, keeping two layers of node values.
template <class Sink>
void march_quadric(const quadric& q, const quadric_grid& g, Sink& sink) {
  const std::int64_t row = g.cells.x + 1, layer = row * (g.cells.y + 1);
  std::vector<double> below(static_cast<std::size_t>(layer)), above(below.size());
  const auto fill = [&](std::vector<double>& values, int k) {
    for (int j = 0; j <= g.cells.y; ++j)
      for (int i = 0; i <= g.cells.x; ++i) values[j * row + i] = node_value(q, node_position(g, i, j, k));
  };
  fill(below, 0);
  for (int k = 0; k < g.cells.z; ++k) {
    fill(above, k + 1);
    for (int j = 0; j < g.cells.y; ++j)
      for (int i = 0; i < g.cells.x; ++i) {
        cube c;
        int negatives = 0;
        for (int v = 0; v < 8; ++v) {
          const int di = v & 1, dj = (v >> 1) & 1, dk = (v >> 2) & 1;
          c.f[v] = (dk ? above : below)[(j + dj) * row + i + di];
          negatives += c.f[v] < 0.0;
        }
        if (negatives == 0 || negatives == 8) continue;  // the surface misses this cube
        for (int v = 0; v < 8; ++v) {
          const int di = v & 1, dj = (v >> 1) & 1, dk = (v >> 2) & 1;
          c.p[v] = node_position(g, i + di, j + dj, k + dk);
          c.node[v] = (k + dk) * layer + (j + dj) * row + i + di;
        }
        for (const auto& tet : cube_tets) march_tet(c, tet, sink);
      }
    std::swap(below, above);
  }
}

// Where on the edge the polynomial vanishes, as t in [0, 1] from the negative
// end: along the edge's line it is the quadratic A t^2 + B t + C, solved in
// the cancellation-free form. Linear interpolation only if rounding fails it.
double crossing_parameter(const quadric& q, const crossing& x) {
  if (x.f_pos == 0.0) return 1.0;
  const vec3 d = x.pos - x.neg;
  const double a = quadric_form(q, d), b = glm::dot(quadric_gradient_at(q, x.neg), d), c = x.f_neg;
  const auto outside = [](double t) { return t < 0.0 ? -t : (t > 1.0 ? t - 1.0 : 0.0); };
  double t = std::numeric_limits<double>::quiet_NaN();
  if (a == 0.0) {
    t = -c / b;
  } else {
    const double root = std::sqrt(std::max(0.0, b * b - 4.0 * a * c));
    const double h = -0.5 * (b + std::copysign(root, b));
    const double t1 = h / a, t2 = c / h;
    t = outside(t1) <= outside(t2) ? t1 : t2;
  }
  if (!std::isfinite(t) || outside(t) > 1e-6) t = x.f_neg / (x.f_neg - x.f_pos);
  return std::clamp(t, 0.0, 1.0);
}

// Counts the triangles quadric_mesher would keep (it also drops the rare
// zero-area triangle with distinct corners, so this may count a few more).
struct triangle_counter {
  double count = 0.0;
  void triangle(const crossing& a, const crossing& b, const crossing& c, const vec3&) {
    count += a.key != b.key && b.key != c.key && a.key != c.key;
  }
  void quad(const crossing& a, const crossing& b, const crossing& c, const crossing& d, const vec3& side) {
    triangle(a, b, c, side);
    triangle(a, c, d, side);
  }
};

// Builds the mesh: one vertex per crossed edge, exactly on the surface.
class quadric_mesher {
 public:
  explicit quadric_mesher(const quadric& q) : q_(q) {}

  void triangle(const crossing& a, const crossing& b, const crossing& c, const vec3& side) {
    int va = vertex(a), vb = vertex(b), vc = vertex(c);
    if (glm::dot(triangle_cross(mesh_, va, vb, vc), side) < 0.0) std::swap(vb, vc);
    emit(va, vb, vc);
  }

  // Orients the quad as a whole (its triangles then agree), and splits it
  // along the shorter diagonal.
  void quad(const crossing& a, const crossing& b, const crossing& c, const crossing& d, const vec3& side) {
    int v[4] = {vertex(a), vertex(b), vertex(c), vertex(d)};
    const auto& p = mesh_.positions;
    if (glm::dot(glm::cross(p[v[2]] - p[v[0]], p[v[3]] - p[v[1]]), side) < 0.0) std::swap(v[1], v[3]);
    if (glm::distance(p[v[0]], p[v[2]]) <= glm::distance(p[v[1]], p[v[3]])) {
      emit(v[0], v[1], v[2]);
      emit(v[0], v[2], v[3]);
    } else {
      emit(v[0], v[1], v[3]);
      emit(v[1], v[2], v[3]);
    }
  }

  triangle_mesh take() {
    fill_missing_normals(mesh_);
    return std::move(mesh_);
  }

 private:
  int vertex(const crossing& x) {
    const auto [it, fresh] = ids_.try_emplace(x.key, 0);
    if (fresh) {
      const double t = crossing_parameter(q_, x);
      const vec3 p = t == 1.0 ? x.pos : x.neg + t * (x.pos - x.neg);
      it->second = add_vertex(mesh_, p, unit_or_zero(quadric_gradient_at(q_, p)), vec2(0.0));
    }
    return it->second;
  }

  void emit(int a, int b, int c) {
    if (is_proper(mesh_, a, b, c)) add_triangle(mesh_, a, b, c, q_.material);
  }

  const quadric& q_;
  triangle_mesh mesh_;
  std::unordered_map<std::int64_t, int> ids_;
};

// Where a bounded quadric (an ellipsoid, or an elliptic cylinder along
// axes the polynomial does not mention) can be: its box cut down to the
// surface's own bounding box, padded. nullopt when it is unbounded, empty or
// a point, or misses the box.
std::optional<std::pair<vec3, vec3>> quadric_surface_bounds(const quadric& q) {
  const glm::dmat3 a(q.a, q.d, q.f, q.d, q.b, q.e, q.f, q.e, q.c);
  const vec3 b(q.g, q.h, q.j);
  bool present[3];
  for (int i = 0; i < 3; ++i) present[i] = a[i] != vec3(0.0) || b[i] != 0.0;
  for (const double sign : {1.0, -1.0}) {
    // The same surface as sign * polynomial; absent axes get a 1 on the
    // diagonal so that the matrix is definite exactly when the rest is.
    glm::dmat3 m = sign * a;
    for (int i = 0; i < 3; ++i)
      if (!present[i]) m[i][i] = 1.0;
    const double scale = std::max({std::abs(m[0][0]), std::abs(m[1][1]), std::abs(m[2][2])});
    const double minor1 = m[0][0], minor2 = m[0][0] * m[1][1] - m[0][1] * m[1][0], minor3 = glm::determinant(m);
    const double tiny = 1e-12;
    if (!(minor1 > tiny * scale && minor2 > tiny * scale * scale && minor3 > tiny * scale * scale * scale)) continue;
    const glm::dmat3 inv = glm::inverse(m);
    const vec3 bs = sign * b;
    const vec3 centre = -(inv * bs);
    const double rho = glm::dot(bs, inv * bs) - sign * q.k;  // surface: y^T m y = rho, y = x - centre
    if (!(rho > 0.0) || !std::isfinite(rho)) return std::nullopt;
    vec3 lo = q.box_min, hi = q.box_max;
    for (int i = 0; i < 3; ++i) {
      if (!present[i]) continue;
      const double half = std::sqrt(rho * inv[i][i]);
      const double pad = 0.02 * half;  // keeps the surface strictly inside the grid
      lo[i] = std::max(lo[i], centre[i] - half - pad);
      hi[i] = std::min(hi[i], centre[i] + half + pad);
    }
    if (!glm::all(glm::lessThan(lo, hi))) return std::nullopt;
    return std::pair{lo, hi};
  }
  return std::nullopt;
}

// The cells are a little smaller than max_edge: a triangle's edges can be as
// long as a tetrahedron's edges, up to the cube's diagonal. A bounded
// surface small for max_edge (a small sphere in a big box) gets a grid over
// its own bounds with at least min_quadric_cells across it, which would
// otherwise fall between the grid nodes and vanish.
quadric_grid quadric_grid_by_size(const quadric& q, double max_edge) {
  const double cell = max_edge / 1.5;
  if (const auto bounds = quadric_surface_bounds(q)) {
    // The surface's own size, where it is bounded, before the box clips it:
    // a hemisphere cut by its box is as small as its sphere, no smaller.
    quadric unclipped = q;
    unclipped.box_min = vec3(-std::numeric_limits<double>::infinity());
    unclipped.box_max = vec3(std::numeric_limits<double>::infinity());
    double smallest = std::numeric_limits<double>::infinity();
    if (const auto whole = quadric_surface_bounds(unclipped))
      for (int i = 0; i < 3; ++i) smallest = std::min(smallest, whole->second[i] - whole->first[i]);
    if (smallest / min_quadric_cells < cell) {
      quadric own = q;
      own.box_min = bounds->first;
      own.box_max = bounds->second;
      return quadric_resolution(own, smallest / min_quadric_cells);
    }
  }
  return quadric_resolution(q, cell);
}

// The largest |eigenvalue| of the quadric's symmetric matrix, by power
// iteration (its norm: the Hessian is twice the matrix).
double quadric_matrix_norm(const quadric& q) {
  const glm::dmat3 m(q.a, q.d, q.f, q.d, q.b, q.e, q.f, q.e, q.c);
  vec3 v = glm::normalize(vec3(1.0, 0.7, 0.4));
  double norm = 0.0;
  for (int i = 0; i < 64; ++i) {
    const vec3 w = m * v;
    norm = glm::length(w);
    if (!(norm > 0.0)) return 0.0;
    v = w / norm;
  }
  return norm;
}

// The smallest radius of curvature over the surface, bounded from below:
// a normal curvature is t.H.t / |grad F| for a unit tangent t, at most
// |H| / |grad F|, taken at the vertices of a march on a coarse grid.
double smallest_curvature_radius(const quadric& q, const quadric_grid& g) {
  const double hessian = 2.0 * quadric_matrix_norm(q);
  if (!(hessian > 0.0)) return std::numeric_limits<double>::infinity();  // a plane
  quadric_grid probe = g;  // fine enough to find a surface that a coarse grid misses
  probe.cells = glm::ivec3(estimate_cells_per_axis / 2);
  quadric_mesher mesher(q);
  march_quadric(q, probe, mesher);
  double radius = std::numeric_limits<double>::infinity();
  for (const vec3& p : mesher.take().positions)
    if (const double slope = glm::length(quadric_gradient_at(q, p)); slope > 0.0)
      radius = std::min(radius, slope / hessian);
  return radius;
}

// The grid for max_edge, made finer where the surface bends faster than
// radians_per_edge per edge (an edge spans up to 1.5 cells), by at most
// max_curvature_shrink per axis.
quadric_grid quadric_grid_for(const quadric& q, double max_edge) {
  const quadric_grid by_size = quadric_grid_by_size(q, max_edge);
  const vec3 cells = (by_size.hi - by_size.lo) / vec3(by_size.cells);
  const double cell = std::max({cells.x, cells.y, cells.z});
  const double bent = smallest_curvature_radius(q, by_size) * radians_per_edge / 1.5;
  if (!(bent < cell)) return by_size;
  quadric bounded = q;
  bounded.box_min = by_size.lo;
  bounded.box_max = by_size.hi;
  return quadric_resolution(bounded, std::max(bent, cell / max_curvature_shrink));
}

// Triangle count of the tessellation: exact on small grids; on big ones,
// counted on a coarse grid and scaled by the squared refinement, since the
// count grows with area / cell^2. (Features smaller than a coarse cell may be
// missed; their share is small by the same scaling.)
double quadric_triangles(const quadric& q, double max_edge) {
  const quadric_grid fine = quadric_grid_for(q, max_edge);
  const int largest = std::max({fine.cells.x, fine.cells.y, fine.cells.z});
  quadric_grid coarse = fine;
  if (largest > estimate_cells_per_axis) {
    const vec3 scaled = glm::ceil(vec3(fine.cells) * (double(estimate_cells_per_axis) / largest));
    coarse.cells = glm::ivec3(glm::max(scaled, vec3(1.0)));
  }
  triangle_counter counter;
  march_quadric(q, coarse, counter);
  return counter.count * std::pow(product(vec3(fine.cells)) / product(vec3(coarse.cells)), 2.0 / 3.0);
}

// ---------------------------------------------------------------------------
// Parametric surfaces

using basis = std::array<double, 4>;

basis bernstein(double t) {
  const double s = 1.0 - t;
  return {s * s * s, 3.0 * t * s * s, 3.0 * t * t * s, t * t * t};
}

basis bernstein_slope(double t) {
  const double s = 1.0 - t;
  return {-3.0 * s * s, 3.0 * s * s - 6.0 * t * s, 6.0 * t * s - 3.0 * t * t, 3.0 * t * t};
}

// Uniform cubic B-spline basis on one span, t in [0, 1].
basis bspline_basis(double t) {
  const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
  return {s * s * s / 6.0, (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0, (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0, t3 / 6.0};
}

basis bspline_slope(double t) {
  const double s = 1.0 - t, t2 = t * t;
  return {-0.5 * s * s, 0.5 * (3.0 * t2 - 4.0 * t), 0.5 * (-3.0 * t2 + 2.0 * t + 1.0), 0.5 * t2};
}

struct surface_sample {
  vec3 point, du, dv;
};

// Tensor-product evaluation over a 4x4 block of control points,
// control(row, col), u along a row.
template <class Control>
surface_sample tensor_sample(Control control, const basis& bu, const basis& su, const basis& bv, const basis& sv) {
  surface_sample s{vec3(0.0), vec3(0.0), vec3(0.0)};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      const vec3& p = control(r, c);
      s.point += bv[r] * bu[c] * p;
      s.du += bv[r] * su[c] * p;
      s.dv += sv[r] * bu[c] * p;
    }
  return s;
}

surface_sample bezier_sample(const std::array<vec3, 16>& control, double u, double v) {
  const auto at = [&](int r, int c) -> const vec3& { return control[4 * r + c]; };
  return tensor_sample(at, bernstein(u), bernstein_slope(u), bernstein(v), bernstein_slope(v));
}

// Span index and local parameter; the end of the last span stays in it.
std::pair<int, double> bspline_span(double x, int spans) {
  BOUNCE_DCHECK(std::isfinite(x));
  const double s = std::clamp(std::floor(x), 0.0, spans - 1.0);
  return {static_cast<int>(s), x - s};
}

surface_sample bspline_sample(const bspline_surface& b, double u, double v) {
  BOUNCE_CHECK(b.rows >= 4 && b.cols >= 4 && b.control.size() == static_cast<std::size_t>(b.rows) * b.cols);
  const auto [su, tu] = bspline_span(u, b.cols - 3);
  const auto [sv, tv] = bspline_span(v, b.rows - 3);
  const auto at = [&](int r, int c) -> const vec3& { return b.control[(sv + r) * b.cols + su + c]; };
  return tensor_sample(at, bspline_basis(tu), bspline_slope(tu), bspline_basis(tv), bspline_slope(tv));
}

// Unit dP/du x dP/dv, or zero where the derivatives vanish or are (nearly)
// parallel, e.g. at a pole where a patch edge collapses to a point.
vec3 normal_of(const surface_sample& s) {
  const vec3 n = glm::cross(s.du, s.dv);
  const double len = glm::length(n);
  const double scale = glm::dot(s.du, s.du) + glm::dot(s.dv, s.dv);
  return len > 1e-10 * scale ? n / len : vec3(0.0);
}

// The normal at uv; where the surface is degenerate, the normal a tiny step
// towards the domain's centre instead (the limit of the normal at a pole).
// Zero if the surface has no tangent plane anywhere near.
template <class Sampler>
vec3 robust_normal(Sampler sample, const surface_sample& here, const vec2& uv, const vec2& centre) {
  vec3 n = normal_of(here);
  for (double step : {1e-7, 1e-5, 1e-3, 1e-1}) {
    if (n != vec3(0.0)) break;
    const vec2 inside = glm::mix(uv, centre, step);
    n = normal_of(sample(inside.x, inside.y));
  }
  return n;
}

// Adds a grid of vertices at parameters us x vs with two triangles per cell,
// split along the shorter diagonal, counter-clockwise in (u, v) (so facing
// dP/du x dP/dv). The grid's border vertices are appended to `border`.
template <class Sampler>
void add_parameter_grid(triangle_mesh& m, const std::vector<double>& us, const std::vector<double>& vs, Sampler sample,
                        const vec2& centre, const vec2& uv_scale, int material, std::vector<int>& border) {
  const int nu = static_cast<int>(us.size()), nv = static_cast<int>(vs.size());
  BOUNCE_CHECK(nu >= 2 && nv >= 2);
  BOUNCE_CHECK_LT(m.positions.size() + double(nu) * nv, double(std::numeric_limits<int>::max()));
  const int base = static_cast<int>(m.positions.size());
  const auto id = [&](int i, int j) { return base + j * nu + i; };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const vec2 uv(us[i], vs[j]);
      const surface_sample s = sample(uv.x, uv.y);
      add_vertex(m, s.point, robust_normal(sample, s, uv, centre), uv * uv_scale);
    }
  const auto& p = m.positions;
  for (int j = 0; j + 1 < nv; ++j)
    for (int i = 0; i + 1 < nu; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (glm::distance(p[a], p[c]) <= glm::distance(p[b], p[d])) {
        add_triangle(m, a, b, c, material);
        add_triangle(m, a, c, d, material);
      } else {
        add_triangle(m, a, b, d, material);
        add_triangle(m, b, c, d, material);
      }
    }
  for (int i = 0; i < nu; ++i) {
    border.push_back(id(i, 0));
    border.push_back(id(i, nv - 1));
  }
  for (int j = 1; j + 1 < nv; ++j) {
    border.push_back(id(0, j));
    border.push_back(id(nu - 1, j));
  }
}

// n + 1 evenly spaced parameters from lo to hi (both exact).
void append_uniform(std::vector<double>& out, double lo, double hi, int n, bool with_end) {
  for (int i = 0; i < n; ++i) out.push_back(lo + (hi - lo) * i / n);
  if (with_end) out.push_back(hi);
}

// Segments along u and along v over the parameter rectangle [lo, hi] so
// that the normal turns by at most radians_per_edge per segment, from its
// turn between samples (a turn finer than the samples is missed).
// `samples` steps per direction.
template <class Sampler>
std::pair<int, int> turn_segments(Sampler sample, const vec2& lo, const vec2& hi, const vec2& centre,
                                  glm::ivec2 samples = glm::ivec2(8)) {
  const int nu = samples.x, nv = samples.y;
  std::vector<vec3> normals(std::size_t(nu + 1) * (nv + 1));  // row j along v, column i along u
  const auto at = [&](int i, int j) -> vec3& { return normals[std::size_t(j) * (nu + 1) + i]; };
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const vec2 uv = lo + (hi - lo) * vec2(double(i) / nu, double(j) / nv);
      at(i, j) = robust_normal(sample, sample(uv.x, uv.y), uv, centre);
    }
  const auto angle = [](const vec3& a, const vec3& b) {
    return a == vec3(0.0) || b == vec3(0.0) ? 0.0 : std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
  };
  // Segments are uniform in the parameter, so the steepest sampled step
  // sets the count: the turn the whole range would have at its rate.
  double along_u = 0.0, along_v = 0.0;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i < nu; ++i) along_u = std::max(along_u, nu * angle(at(i, j), at(i + 1, j)));
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j < nv; ++j) along_v = std::max(along_v, nv * angle(at(i, j), at(i, j + 1)));
  return {segments_for(along_u, radians_per_edge, 1, max_patch_segments),
          segments_for(along_v, radians_per_edge, 1, max_patch_segments)};
}

// Segments per direction of one Bezier patch. |dP/du| <= 3 max |control
// difference along u|, so steps of 1/n in u are at most max_edge long; and
// more where the patch turns (turn_segments).
std::pair<int, int> bezier_resolution(const std::array<vec3, 16>& c, double max_edge) {
  double along_u = 0.0, along_v = 0.0;
  for (int r = 0; r < 4; ++r)
    for (int k = 0; k < 3; ++k) {
      along_u = std::max(along_u, glm::distance(c[4 * r + k], c[4 * r + k + 1]));
      along_v = std::max(along_v, glm::distance(c[4 * k + r], c[4 * (k + 1) + r]));
    }
  const auto sample = [&](double u, double v) { return bezier_sample(c, u, v); };
  const auto [turn_u, turn_v] = turn_segments(sample, vec2(0.0), vec2(1.0), vec2(0.5));
  return {std::max(turn_u, segments_for(3.0 * along_u, max_edge, 1, max_patch_segments)),
          std::max(turn_v, segments_for(3.0 * along_v, max_edge, 1, max_patch_segments))};
}

// Segments of one B-spline span (span index along u, or along v when
// !along_u). On a uniform cubic span |dP/du| <= max |control difference|;
// and more where the span turns (turn_segments, across the whole surface).
int bspline_span_segments(const bspline_surface& b, int span, bool along_u, double max_edge) {
  const int lines = along_u ? b.rows : b.cols;
  double longest = 0.0;
  for (int line = 0; line < lines; ++line)
    for (int k = span; k < span + 3; ++k) {
      const int here = along_u ? line * b.cols + k : k * b.cols + line;
      const int next = along_u ? here + 1 : here + b.cols;
      longest = std::max(longest, glm::distance(b.control[here], b.control[next]));
    }
  const vec2 spans(b.cols - 3, b.rows - 3);
  const vec2 lo = along_u ? vec2(span, 0.0) : vec2(0.0, span);
  const vec2 hi = along_u ? vec2(span + 1.0, spans.y) : vec2(spans.x, span + 1.0);
  const auto sample = [&](double u, double v) { return bspline_sample(b, u, v); };
  const glm::ivec2 samples = along_u ? glm::ivec2(8, 8 * (b.rows - 3)) : glm::ivec2(8 * (b.cols - 3), 8);
  const auto [turn_u, turn_v] = turn_segments(sample, lo, hi, 0.5 * spans, samples);
  return std::max(along_u ? turn_u : turn_v, segments_for(longest, max_edge, 1, max_patch_segments));
}

// Parameter lines of the whole B-spline surface along one direction.
std::vector<double> bspline_lines(const bspline_surface& b, bool along_u, double max_edge) {
  const int spans = (along_u ? b.cols : b.rows) - 3;
  std::vector<double> out;
  for (int s = 0; s < spans; ++s)
    append_uniform(out, s, s + 1.0, bspline_span_segments(b, s, along_u, max_edge), s + 1 == spans);
  return out;
}

double bspline_segments_total(const bspline_surface& b, bool along_u, double max_edge) {
  const int spans = (along_u ? b.cols : b.rows) - 3;
  double total = 0.0;
  for (int s = 0; s < spans; ++s) total += bspline_span_segments(b, s, along_u, max_edge);
  return total;
}

}  // namespace

// ---------------------------------------------------------------------------
// Public functions

triangle_mesh triangulate(const polygon_mesh& mesh, std::size_t* dropped) {
  triangle_mesh out;
  std::size_t skipped = 0;
  // Corners share a vertex when position, normal and uv agree; without given
  // normals each face has its own (Newell) normal, so the face is part of the key.
  std::map<std::array<int, 4>, int> shared;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const polygon_face& face = mesh.faces[f];
    const std::vector<corner> corners = distinct_corners(face);
    std::vector<vec3> points;
    for (const corner& c : corners) {
      BOUNCE_DCHECK(c.position >= 0 && c.position < static_cast<int>(mesh.positions.size()));
      points.push_back(mesh.positions[c.position]);
    }
    const vec3 newell = corners.size() >= 3 ? newell_normal(points) : vec3(0.0);
    if (corners.size() < 3 || !has_area(points, newell)) {
      ++skipped;
      continue;
    }
    const vec3 face_normal = glm::normalize(newell);
    const auto vertex = [&](const corner& c) {
      const std::array<int, 4> key{c.position, c.normal, c.uv, c.normal < 0 ? static_cast<int>(f) : -1};
      const auto [it, fresh] = shared.try_emplace(key, 0);
      if (fresh) {
        const vec3 given = c.normal < 0 ? vec3(0.0) : unit_or_zero(mesh.normals[c.normal]);
        const vec2 uv = c.uv < 0 ? vec2(0.0) : mesh.uvs[c.uv];
        it->second = add_vertex(out, mesh.positions[c.position], given != vec3(0.0) ? given : face_normal, uv);
      }
      return it->second;
    };
    for (const glm::ivec3& t : ear_clip(project_to_plane(points, newell)))
      add_triangle(out, vertex(corners[t.x]), vertex(corners[t.y]), vertex(corners[t.z]), face.material);
  }
  if (dropped) *dropped = skipped;
  return out;
}

triangle_mesh tessellate(const sphere& s, double max_edge) {
  BOUNCE_CHECK_GT(max_edge, 0.0);
  BOUNCE_CHECK_GT(s.radius, 0.0);
  const sphere_grid g = sphere_resolution(s, max_edge);
  triangle_mesh m;
  // Polar axis y, from the south pole (v = 0) to the north pole (v = 1).
  const auto add = [&](double u, double v) {
    const double theta = pi * v, phi = 2.0 * pi * u;
    const vec3 dir =
        glm::normalize(vec3(std::sin(theta) * std::cos(phi), -std::cos(theta), -std::sin(theta) * std::sin(phi)));
    return add_vertex(m, s.center + s.radius * dir, dir, vec2(u, v));
  };
  const int south = add(0.5, 0.0);
  for (int k = 1; k < g.rows; ++k)
    for (int j = 0; j < g.around; ++j) add(double(j) / g.around, double(k) / g.rows);
  const int north = add(0.5, 1.0);
  const auto ring = [&](int k, int j) { return 1 + (k - 1) * g.around + j % g.around; };
  for (int j = 0; j < g.around; ++j) {
    add_triangle(m, south, ring(1, j + 1), ring(1, j), s.material);
    for (int k = 1; k + 1 < g.rows; ++k) {
      add_triangle(m, ring(k, j), ring(k, j + 1), ring(k + 1, j + 1), s.material);
      add_triangle(m, ring(k, j), ring(k + 1, j + 1), ring(k + 1, j), s.material);
    }
    add_triangle(m, ring(g.rows - 1, j), ring(g.rows - 1, j + 1), north, s.material);
  }
  return m;
}

triangle_mesh tessellate(const quadric& q, double max_edge) {
  BOUNCE_CHECK_GT(max_edge, 0.0);
  quadric_mesher mesher(q);
  march_quadric(q, quadric_grid_for(q, max_edge), mesher);
  return mesher.take();
}

triangle_mesh tessellate(const bezier_surface& b, double max_edge) {
  BOUNCE_CHECK_GT(max_edge, 0.0);
  triangle_mesh m;
  std::vector<int> border;
  for (const std::array<vec3, 16>& patch : b.patches) {
    const auto [nu, nv] = bezier_resolution(patch, max_edge);
    std::vector<double> us, vs;
    append_uniform(us, 0.0, 1.0, nu, true);
    append_uniform(vs, 0.0, 1.0, nv, true);
    const auto sample = [&](double u, double v) { return bezier_sample(patch, u, v); };
    add_parameter_grid(m, us, vs, sample, vec2(0.5), vec2(1.0), b.material, border);
  }
  // Patches meet along shared edges (and at poles): one smooth mesh.
  weld(m, std::move(border), 1e-9 * bounding_diagonal(m.positions));
  fill_missing_normals(m);
  return m;
}

triangle_mesh tessellate(const bspline_surface& b, double max_edge) {
  BOUNCE_CHECK_GT(max_edge, 0.0);
  const std::vector<double> us = bspline_lines(b, true, max_edge), vs = bspline_lines(b, false, max_edge);
  const vec2 spans(b.cols - 3, b.rows - 3);
  triangle_mesh m;
  std::vector<int> border;
  const auto sample = [&](double u, double v) { return bspline_sample(b, u, v); };
  add_parameter_grid(m, us, vs, sample, 0.5 * spans, 1.0 / spans, b.material, border);
  // Closes seams of periodic surfaces and collapsed edges (poles).
  weld(m, std::move(border), 1e-9 * bounding_diagonal(m.positions));
  fill_missing_normals(m);
  return m;
}

triangle_mesh tessellate(const surface& s, double max_edge, std::size_t* dropped) {
  BOUNCE_CHECK_GT(max_edge, 0.0);
  if (dropped) *dropped = 0;
  return std::visit(
      [&](const auto& g) -> triangle_mesh {
        if constexpr (std::is_same_v<std::decay_t<decltype(g)>, polygon_mesh>)
          return triangulate(g, dropped);
        else
          return tessellate(g, max_edge);
      },
      s.geometry);
}

std::size_t estimate_triangles(const surface& s, double max_edge) {
  BOUNCE_CHECK_GT(max_edge, 0.0);
  const auto count = [&](const auto& g) -> double {
    using T = std::decay_t<decltype(g)>;
    if constexpr (std::is_same_v<T, polygon_mesh>) {
      double n = 0.0;
      for (const polygon_face& f : g.faces) n += std::max(0.0, double(f.position.size()) - 2.0);
      return n;
    } else if constexpr (std::is_same_v<T, sphere>) {
      return sphere_triangles(sphere_resolution(g, max_edge));
    } else if constexpr (std::is_same_v<T, quadric>) {
      return quadric_triangles(g, max_edge);
    } else if constexpr (std::is_same_v<T, bezier_surface>) {
      double n = 0.0;  // before welding, so an upper bound
      for (const auto& patch : g.patches) {
        const auto [nu, nv] = bezier_resolution(patch, max_edge);
        n += 2.0 * nu * nv;
      }
      return n;
    } else {
      return 2.0 * bspline_segments_total(g, true, max_edge) * bspline_segments_total(g, false, max_edge);
    }
  };
  return saturate(std::visit(count, s.geometry));
}

vec3 bezier_point(const std::array<vec3, 16>& control, double u, double v) {
  return bezier_sample(control, u, v).point;
}

vec3 bezier_normal(const std::array<vec3, 16>& control, double u, double v) {
  const auto sample = [&](double x, double y) { return bezier_sample(control, x, y); };
  return robust_normal(sample, sample(u, v), vec2(u, v), vec2(0.5));
}

vec3 bspline_point(const bspline_surface& b, double u, double v) {
  return bspline_sample(b, u, v).point;
}

vec3 bspline_normal(const bspline_surface& b, double u, double v) {
  const auto sample = [&](double x, double y) { return bspline_sample(b, x, y); };
  return robust_normal(sample, sample(u, v), vec2(u, v), 0.5 * vec2(b.cols - 3, b.rows - 3));
}

double quadric_value(const quadric& q, const vec3& p) {
  return q.a * p.x * p.x + q.b * p.y * p.y + q.c * p.z * p.z +
         2.0 * (q.d * p.x * p.y + q.e * p.y * p.z + q.f * p.x * p.z + q.g * p.x + q.h * p.y + q.j * p.z) + q.k;
}

vec3 quadric_gradient(const quadric& q, const vec3& p) {
  return quadric_gradient_at(q, p);
}

}  // namespace bounce
