// Coplanar overlaps cut out of the surface behind, and the ground under
// solids (coplanar_cut.h). The polygon boolean is Clipper's (Debian's
// libpolyclipping, integer coordinates); what is left is triangulated on
// the same integers (polygon_triangulation.h), so every orientation test is
// exact.
#include "mesh/coplanar_cut.h"

#include "base/random_stream.h"
#include "mesh/plane_pieces.h"

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

// The cover: the region of a plane that the pieces taken so far hold, as
// polygons (an outer ring and its holes) in a coarse grid of their boxes.
// A piece's triangles are clipped only against the polygons whose boxes
// overlap theirs (most pieces, surfaces that share an edge or lie apart in
// the plane, meet none and skip Clipper), and a small piece that overlaps
// the cover is merged with the polygons it met: stacked copies of one
// triangle then leave one polygon, not thousands that every later piece is
// clipped against.
class cover_set {
 public:
  // The live polygons whose boxes overlap one of `paths`' boxes by more
  // than the rounding of the integer frame (touching does not count).
  std::vector<int> overlapping(const ClipperLib::Paths& paths) {
    std::vector<int> out;
    ++query_;
    auto take = [&](int i) {
      if (!alive_[std::size_t(i)] || seen_[std::size_t(i)] == query_) return;
      for (const ClipperLib::Path& path : paths)
        if (overlap(bounds(path), boxes_[std::size_t(i)])) {
          seen_[std::size_t(i)] = query_;
          out.push_back(i);
          return;
        }
    };
    for (int i : large_) take(i);
    for (const ClipperLib::Path& path : paths) {
      const box b = bounds(path);
      for (long long x = cell(b.x0); x <= cell(b.x1); ++x)
        for (long long y = cell(b.y0); y <= cell(b.y1); ++y) {
          const auto it = cells_.find({x, y});
          if (it != cells_.end())
            for (int i : it->second) take(i);
        }
    }
    return out;
  }
  const ClipperLib::Paths& polygon(int i) const { return polygons_[std::size_t(i)]; }
  // Each path a polygon of its own (a piece's triangles).
  void add_each(const ClipperLib::Paths& paths) {
    for (const ClipperLib::Path& path : paths) add({path});
  }
  // Each outer ring of `region` with its holes (islands in holes: their own).
  void add_region(const ClipperLib::PolyNode& node) {
    for (const ClipperLib::PolyNode* outer : node.Childs) {
      ClipperLib::Paths polygon{outer->Contour};
      for (const ClipperLib::PolyNode* hole : outer->Childs) polygon.push_back(hole->Contour);
      add(polygon);
      for (const ClipperLib::PolyNode* hole : outer->Childs) add_region(*hole);
    }
  }
  void add(const ClipperLib::Paths& polygon) {
    if (polygon.empty() || polygon[0].size() < 3) return;
    const box b = bounds(polygon[0]);
    const int index = int(polygons_.size());
    polygons_.push_back(polygon);
    boxes_.push_back(b);
    alive_.push_back(true);
    seen_.push_back(0);
    const long long x0 = cell(b.x0), x1 = cell(b.x1), y0 = cell(b.y0), y1 = cell(b.y1);
    if ((x1 - x0 + 1) * (y1 - y0 + 1) > 64) {
      large_.push_back(index);
      return;
    }
    for (long long x = x0; x <= x1; ++x)
      for (long long y = y0; y <= y1; ++y) cells_[{x, y}].push_back(index);
  }
  // Drops polygon i (its grid entries stay, skipped from now on).
  void remove(int i) {
    alive_[std::size_t(i)] = false;
    ClipperLib::Paths().swap(polygons_[std::size_t(i)]);
    std::erase(large_, i);
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
  std::vector<ClipperLib::Paths> polygons_;               // outer ring first
  std::vector<box> boxes_;
  std::vector<bool> alive_;
  std::vector<unsigned> seen_;
  unsigned query_ = 0;
  std::vector<int> large_;
  std::map<std::pair<long long, long long>, std::vector<int>> cells_;
};

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
    cover_set cover;
    std::map<std::pair<long long, long long>, vec2> cover_corners;
    for (const piece& p : pieces) {
      triangle_mesh& m = tessellated[p.surface];
      const ClipperLib::Paths own = piece_paths(m, p.triangles, frame);
      if (own.empty()) continue;
      // Only the piece's triangles whose boxes overlap the cover take part:
      // a floor of a million triangles under one rug is one piece, and
      // Clipper on all of it costs far more than on the few under the rug.
      piece under = p;
      under.triangles.clear();
      ClipperLib::Paths subject;
      std::vector<int> met;  // the cover's polygons those overlap
      for (int t : p.triangles) {
        const ClipperLib::Paths triangle = piece_paths(m, {t}, frame);
        if (triangle.empty()) continue;
        const std::vector<int> near = cover.overlapping(triangle);
        if (near.empty()) continue;
        under.triangles.push_back(t);
        subject.push_back(triangle[0]);
        met.insert(met.end(), near.begin(), near.end());
      }
      std::sort(met.begin(), met.end());
      met.erase(std::unique(met.begin(), met.end()), met.end());
      stats.polygons_clipped_against += met.size();
      bool overlaps = false;
      if (!met.empty()) {
        ClipperLib::Paths over;
        for (int i : met) over.insert(over.end(), cover.polygon(i).begin(), cover.polygon(i).end());
        ClipperLib::PolyTree after;
        ClipperLib::Clipper cut;
        cut.PreserveCollinear(true);
        cut.StrictlySimple(true);
        cut.AddPaths(subject, ClipperLib::ptSubject, true);
        cut.AddPaths(over, ClipperLib::ptClip, true);
        cut.Execute(ClipperLib::ctDifference, after, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
        double area_before = 0.0;  // the triangles do not overlap: their sum is their union's
        for (const ClipperLib::Path& path : subject) area_before += std::abs(ClipperLib::Area(path));
        const double area_after = tree_area(after);
        // Only touching the cover (shared edges) leaves the area as it was.
        overlaps = area_before - area_after > 1e-9 * area_before;
        if (overlaps) {
          double old_area = 0.0, new_area = 0.0;
          for (int t : under.triangles) old_area += 0.5 * glm::length(triangle_cross(m, t));
          const std::size_t first_new = m.triangles.size();
          if (replace_piece(m, under, after, frame, cover_corners, removed[p.surface])) {
            for (std::size_t t = first_new; t < m.triangles.size(); ++t)
              new_area += 0.5 * glm::length(triangle_cross(m, int(t)));
            ++stats.surfaces_cut;
            stats.area_removed += old_area - new_area;
          } else {
            ++stats.pieces_left_uncut;  // the overlap stays: said, not hidden
          }
        }
      }
      // The cover grows by the piece. A small piece that overlapped it is
      // merged with the polygons it met (stacked copies then stay one
      // polygon); a large one adds its triangles, which may overlap what
      // they cover.
      std::size_t met_corners = 0;
      for (int i : met)
        for (const ClipperLib::Path& ring : cover.polygon(i)) met_corners += ring.size();
      if (overlaps && own.size() <= 64 && met_corners <= 4096) {
        ClipperLib::Clipper merge;
        merge.AddPaths(own, ClipperLib::ptSubject, true);
        for (int i : met) merge.AddPaths(cover.polygon(i), ClipperLib::ptClip, true);
        ClipperLib::PolyTree merged;
        merge.Execute(ClipperLib::ctUnion, merged, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
        for (int i : met) cover.remove(i);
        cover.add_region(merged);
      } else {
        cover.add_each(own);
      }
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
