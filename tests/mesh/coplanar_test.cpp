// Coplanar overlaps (coplanar_cut.h): the triangulation of polygons with
// holes, and the official Cornell box, whose light lies in (or 0.1 mm
// under) an uncut ceiling, through the mesher and the ray scene.
#include <cmath>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "cornell_files.h"
#include "mesh/coplanar_cut.h"
#include "mesh/patch_mesh.h"
#include "mesh_builders.h"
#include "scene/camera_math.h"
#include "scene/framing.h"
#include "scene/scene_info.h"
#include "scene/scene_io.h"
#include "test_files.h"
#include "trace/ray_scene.h"

namespace bounce {
namespace {

using test_support::scratch_dir;
using test_support::source_path;

long long doubled_area(const std::vector<int_point>& p, const std::array<int, 3>& t) {
  const int_point a = p[t[0]], b = p[t[1]], c = p[t[2]];
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Every triangle counter-clockwise and their areas summing to the
// polygon's: no overlap, no gap.
void expect_tiles(const std::vector<int_point>& outer, const std::vector<std::vector<int_point>>& holes,
                  long long doubled_expected) {
  const auto triangles = triangulate_with_holes(outer, holes);
  std::vector<int_point> all = outer;
  for (const auto& h : holes) all.insert(all.end(), h.begin(), h.end());
  long long sum = 0;
  for (const auto& t : triangles) {
    const long long a = doubled_area(all, t);
    EXPECT_GT(a, 0);
    sum += a;
  }
  EXPECT_EQ(sum, doubled_expected);
  // Every corner is used (no T-vertex left on the outline).
  std::vector<bool> used(all.size(), false);
  for (const auto& t : triangles)
    for (int k : t) used[k] = true;
  for (std::size_t i = 0; i < all.size(); ++i) EXPECT_TRUE(used[i]) << i;
}

TEST(CoplanarCut, TriangulatesASquareWithAHole) {
  expect_tiles({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{3, 3}, {3, 6}, {6, 6}, {6, 3}}}, 2 * (100 - 9));
}

TEST(CoplanarCut, TriangulatesTwoHolesAndStraightCorners) {
  // An L shape with corners along its straight sides, two holes.
  const std::vector<int_point> outer = {{0, 0},   {5, 0},   {10, 0}, {20, 0}, {20, 10},
                                        {10, 10}, {10, 20}, {5, 20}, {0, 20}, {0, 10}};
  const std::vector<std::vector<int_point>> holes = {{{2, 2}, {2, 4}, {4, 4}, {4, 2}},
                                                     {{12, 3}, {12, 7}, {18, 7}, {18, 3}}};
  expect_tiles(outer, holes, 2 * (300 - 4 - 24));
}

TEST(CoplanarCut, TriangulationIsConstrainedDelaunay) {
  // A floor with a row of footprints: ear clipping alone left fans of
  // slivers from the holes' corners across the floor. Every edge that is
  // not the polygon's or a hole's must pass the empty-circle test.
  const std::vector<int_point> outer = {{0, 0}, {1000, 0}, {1000, 400}, {0, 400}};
  std::vector<std::vector<int_point>> holes;
  for (int i = 0; i < 6; ++i) {
    const long long x = 60 + 150 * i, y = 150 + 20 * (i % 3);
    holes.push_back({{x, y}, {x, y + 90}, {x + 70, y + 90}, {x + 70, y}});
  }
  const auto triangles = triangulate_with_holes(outer, holes);
  std::vector<int_point> all = outer;
  for (const auto& h : holes) all.insert(all.end(), h.begin(), h.end());
  std::set<std::pair<int, int>> constrained;
  auto key = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  for (int i = 0; i < 4; ++i) constrained.insert(key(i, (i + 1) % 4));
  for (int h = 0; h < 6; ++h)
    for (int i = 0; i < 4; ++i) constrained.insert(key(4 + 4 * h + i, 4 + 4 * h + (i + 1) % 4));
  std::map<std::pair<int, int>, std::vector<int>> by_edge;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) by_edge[key(triangles[t][k], triangles[t][(k + 1) % 3])].push_back(int(t));
  int checked = 0;
  for (const auto& [edge, list] : by_edge) {
    if (constrained.count(edge) || list.size() != 2) continue;
    const auto& t = triangles[std::size_t(list[0])];
    int far = -1;
    for (int k : triangles[std::size_t(list[1])])
      if (k != edge.first && k != edge.second) far = k;
    // In-circle determinant, in long double: coordinates are small here.
    const int_point a = all[t[0]], b = all[t[1]], c = all[t[2]], d = all[std::size_t(far)];
    const long double adx = a.x - d.x, ady = a.y - d.y, bdx = b.x - d.x, bdy = b.y - d.y, cdx = c.x - d.x,
                      cdy = c.y - d.y;
    const long double det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) -
                            (bdx * bdx + bdy * bdy) * (adx * cdy - cdx * ady) +
                            (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
    EXPECT_LE(det, 0.0L) << "edge " << edge.first << "-" << edge.second;
    ++checked;
  }
  EXPECT_GT(checked, 20);
  expect_tiles(outer, holes, 2 * (1000 * 400 - 6 * 70 * 90));
}

scene load_official(const scratch_dir& dir, const std::string& light_y) {
  scene s;
  load_report report;
  EXPECT_TRUE(load_scene(write_official_cornell(dir, light_y), s, report)) << report.error;
  return s;
}

scene load_embedded() {
  scene s;
  load_report report;
  EXPECT_TRUE(load_scene(source_path("assets/cornell_box/cornell_box.json"), s, report)) << report.error;
  return s;
}

std::map<std::string, double> areas_by_surface(const scene& s, const patch_mesh& m) {
  std::map<std::string, double> out;
  for (std::size_t e = 0; e < m.element_count(); ++e) out[s.surfaces[m.element_surfaces[e]].name] += m.element_areas[e];
  return out;
}

// Total length of the edges of `surface` that only one of its elements
// has: the outline, plus every T-vertex's long edge and its short ones.
double outline_length(const patch_mesh& m, int surface) {
  std::map<std::pair<int, int>, int> uses;
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    if (m.element_surfaces[e] != surface) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = m.elements[e][k], b = m.elements[e][(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  double length = 0.0;
  for (const auto& [edge, n] : uses)
    if (n == 1) length += glm::length(m.positions[edge.first] - m.positions[edge.second]);
  return length;
}

int surface_named(const scene& s, const std::string& name) {
  for (std::size_t i = 0; i < s.surfaces.size(); ++i)
    if (s.surfaces[i].name == name) return int(i);
  ADD_FAILURE() << "no surface " << name;
  return -1;
}

class OfficialCornell : public ::testing::TestWithParam<const char*> {};

TEST_P(OfficialCornell, MesherCutsTheLightOutOfTheCeiling) {
  scratch_dir dir;
  const scene s = load_official(dir, GetParam());
  patch_mesh mesh;
  std::string error;
  mesher_params params;
  params.max_edge = 60.0;
  ASSERT_TRUE(make_patch_mesh(s, params, mesh, error)) << error;
  const std::map<std::string, double> areas = areas_by_surface(s, mesh);
  // The light keeps all its area; the ceiling loses exactly the light's.
  const double light = 130.0 * 105.0, ceiling = 556.0 * 559.2;
  EXPECT_NEAR(areas.at("light"), light, light * 1e-9);
  EXPECT_NEAR(areas.at("ceiling"), ceiling - light, ceiling * 1e-9);
  // Everything else as in the embedded box, whose ceiling is cut by hand.
  patch_mesh embedded;
  const scene e = load_embedded();
  ASSERT_TRUE(make_patch_mesh(e, params, embedded, error)) << error;
  for (const auto& [name, area] : areas_by_surface(e, embedded)) EXPECT_NEAR(areas.at(name), area, area * 1e-9) << name;
  // No element of the ceiling inside the light's rectangle.
  const int ceiling_surface = surface_named(s, "ceiling");
  for (std::size_t el = 0; el < mesh.element_count(); ++el) {
    if (mesh.element_surfaces[el] != ceiling_surface) continue;
    vec3 c(0.0);
    for (int k = 0; k < 3; ++k) c += mesh.positions[mesh.elements[el][k]] / 3.0;
    EXPECT_FALSE(c.x > 213 && c.x < 343 && c.z > 227 && c.z < 332) << el;
  }
  // Conforming: the ceiling's one-sided edges are its outline and the
  // hole's, nothing more (a T-vertex would add its edges).
  EXPECT_NEAR(outline_length(mesh, ceiling_surface), 2 * (556 + 559.2) + 2 * (130 + 105), 1e-6);
  EXPECT_NEAR(outline_length(mesh, surface_named(s, "light")), 2 * (130 + 105), 1e-6);
}

TEST_P(OfficialCornell, RaysHitTheLightNotTheCeiling) {
  scratch_dir dir;
  const scene s = load_official(dir, GetParam());
  const ray_scene rays(s);
  const int light = surface_named(s, "light"), ceiling = surface_named(s, "ceiling");
  // From the camera and from inside the box, obliquely (straight up, the
  // traversal happened to find the light first even without the cut).
  int checked = 0;
  for (const vec3 origin : {vec3(278, 273, -800), vec3(100, 500, 50), vec3(500, 400, 500)})
    for (double x = 4; x < 556; x += 6.5)
      for (double z = 4; z < 559; z += 6.5) {
        const vec3 target(x, 548.8, z), d = target - origin;
        const auto hit = rays.intersect(origin, glm::normalize(d));
        if (!hit || hit->t < glm::length(d) - 1.0) continue;  // blocked on the way
        ++checked;
        const bool under_light = x > 213 && x < 343 && z > 227 && z < 332;
        EXPECT_EQ(hit->surface, under_light ? light : ceiling)
            << x << "," << z << ": " << s.surfaces[hit->surface].name << " at t = " << hit->t;
      }
  EXPECT_GT(checked, 10000);
  EXPECT_NEAR(rays.emitter_area(), 130.0 * 105.0, 1e-6);  // the emitter keeps its area
}

INSTANTIATE_TEST_SUITE_P(LightHeights, OfficialCornell, ::testing::Values("548.8", "548.7"),
                         [](const auto& info) { return std::string(info.param) == "548.8" ? "InPlane" : "Under"; });

// Tessellates every surface and runs the cut, as the mesher does.
coplanar_cut_stats cut(const scene& s, std::vector<triangle_mesh>& tessellated) {
  std::vector<bool> flat;
  for (const surface& surf : s.surfaces) {
    tessellated.push_back(tessellate(surf, 60.0));
    flat.push_back(std::holds_alternative<polygon_mesh>(surf.geometry));
  }
  const bounds3 b = scene_bounds(s);
  return cut_coplanar_overlaps(tessellated, flat, s.materials, glm::length(b.max - b.min));
}

double area(const triangle_mesh& m) {
  double sum = 0.0;
  for (const glm::ivec3& t : m.triangles)
    sum += 0.5 * glm::length(glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]));
  return sum;
}

TEST(CoplanarCut, EmbeddedBoxIsAlreadyCut) {
  // Its light only touches the ceiling's cells along their edges.
  std::vector<triangle_mesh> tessellated;
  EXPECT_EQ(cut(load_embedded(), tessellated).surfaces_cut, 0u);
}

TEST(CoplanarCut, EmitterKeepsItsAreaEvenBehindTheCeiling) {
  // 0.1 mm above the ceiling (behind it): still the ceiling is cut, so the
  // light is seen and shoots with its whole area.
  scratch_dir dir;
  const scene s = load_official(dir, "548.9");
  std::vector<triangle_mesh> tessellated;
  const coplanar_cut_stats stats = cut(s, tessellated);
  EXPECT_EQ(stats.surfaces_cut, 1u);
  EXPECT_NEAR(stats.area_removed, 130.0 * 105.0, 1e-6);
  EXPECT_NEAR(area(tessellated[surface_named(s, "light")]), 130.0 * 105.0, 1e-6);
  EXPECT_NEAR(area(tessellated[surface_named(s, "ceiling")]), 556.0 * 559.2 - 130.0 * 105.0, 1e-6);
}

TEST(CoplanarCut, SurfacesFartherApartThanTheToleranceStayWhole) {
  // Tolerance: 5e-4 of the diagonal (0.48 mm here). At 5 mm under the
  // ceiling the light is a separate plane; at 0.3 mm it is not.
  scratch_dir dir;
  std::vector<triangle_mesh> far, near;
  const scene s = load_official(dir, "543.8");
  EXPECT_EQ(cut(s, far).surfaces_cut, 0u);
  EXPECT_NEAR(area(far[surface_named(s, "ceiling")]), 556.0 * 559.2, 1e-6);
  EXPECT_EQ(cut(load_official(dir, "548.5"), near).surfaces_cut, 1u);
}

// CAD exports give every triangle an object of its own. Squares 1 x 1,
// each a surface, stacked along the diagonal d apart: surface i is covered
// by i + 1 (the later surface ranks higher), so all but the last keep an
// L of area 2d - d^2, and the plane keeps the union's area. The work stays
// linear: each piece is clipped against the cover merged so far (one
// polygon; 1,000 in all), not against every square before it (n^2 / 2).
TEST(CoplanarCut, ManyStackedSurfacesCostWhatTheirOverlapsCost) {
  constexpr int n = 1000;
  constexpr double d = 1e-3;
  scene s;
  test_support::add_material(s, rgb(0.5));
  for (int i = 0; i < n; ++i) {
    const double o = i * d;
    test_support::add_polygon(s, {{o, 0, o}, {o, 0, o + 1}, {o + 1, 0, o + 1}, {o + 1, 0, o}}, 0);
  }
  std::vector<triangle_mesh> tessellated;
  const coplanar_cut_stats stats = cut(s, tessellated);
  EXPECT_EQ(stats.surfaces_cut, std::size_t(n - 1));
  EXPECT_EQ(stats.pieces_left_uncut, 0u);
  double total = 0.0;
  for (int i = 0; i < n; ++i) {
    const double expected = i == n - 1 ? 1.0 : 2 * d - d * d;
    EXPECT_NEAR(area(tessellated[std::size_t(i)]), expected, 1e-7) << "surface " << i;
    total += area(tessellated[std::size_t(i)]);
  }
  EXPECT_NEAR(total, 1.0 + (n - 1) * (2 * d - d * d), 1e-6);
  EXPECT_LE(stats.polygons_clipped_against, std::size_t(2 * n));
}

// The same plane tiled by 5,000 triangles, each a surface: they share
// edges and nothing is cut; each is clipped only against its neighbours
// (2,500 polygons in all).
TEST(CoplanarCut, ManyTouchingSurfacesAreNotCut) {
  constexpr int side = 50;
  scene s;
  test_support::add_material(s, rgb(0.5));
  for (int x = 0; x < side; ++x)
    for (int z = 0; z < side; ++z)
      for (const bool upper : {false, true}) {
        const vec3 a(x, 0, z), b(x, 0, z + 1), c(x + 1, 0, z + 1), e(x + 1, 0, z);
        if (upper)
          test_support::add_polygon(s, {a, b, c}, 0);
        else
          test_support::add_polygon(s, {a, c, e}, 0);
      }
  std::vector<triangle_mesh> tessellated;
  const coplanar_cut_stats stats = cut(s, tessellated);
  EXPECT_EQ(stats.surfaces_cut, 0u);
  double total = 0.0;
  for (const triangle_mesh& m : tessellated) total += area(m);
  EXPECT_NEAR(total, double(side * side), 1e-9);
  EXPECT_LE(stats.polygons_clipped_against, std::size_t(4 * side * side));
}

// ---- contacts: the ground under solids ----

// An axis-aligned box [lo, hi] with outward faces, as a solid; without its
// bottom or top face when asked (open boxes and tubes).
void add_solid_box(scene& s, vec3 lo, vec3 hi, int material, bool bottom = true, bool top = true) {
  const vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                     {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  // Counter-clockwise seen from outside.
  const int faces[6][4] = {{3, 2, 1, 0}, {4, 5, 6, 7}, {0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}};
  for (int f = 0; f < 6; ++f) {
    if ((f == 4 && !bottom) || (f == 5 && !top)) continue;
    test_support::add_polygon(s, {c[faces[f][0]], c[faces[f][1]], c[faces[f][2]], c[faces[f][3]]}, material);
  }
}

// A 4 x 4 floor facing up at y = 0 under a lamp, and nothing else yet.
scene floor_under_a_lamp() {
  scene s;
  const int lamp = test_support::add_material(s, rgb(0.0), rgb(1.0));
  test_support::add_material(s, rgb(0.5));
  test_support::add_polygon(s, {{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}}, 1, "floor");
  test_support::add_polygon(s, {{-0.5, 3, -0.5}, {0.5, 3, -0.5}, {0.5, 3, 0.5}, {-0.5, 3, 0.5}}, lamp, "lamp");
  return s;
}

struct floor_cut {
  contact_cut_stats stats;
  double floor_area = 0.0;
  patch_mesh mesh;
};

floor_cut cut_floor(const scene& s) {
  floor_cut out;
  std::vector<triangle_mesh> tessellated;
  std::vector<bool> flat;
  for (const surface& surf : s.surfaces) {
    tessellated.push_back(tessellate(surf, 1.0));
    flat.push_back(std::holds_alternative<polygon_mesh>(surf.geometry));
  }
  const bounds3 b = scene_bounds(s);
  out.stats = cut_buried_contacts(tessellated, flat, glm::length(b.max - b.min), 0.025);
  out.floor_area = area(tessellated[0]);
  out.mesh = test_support::mesh_of(s, 0.25);
  return out;
}

// Whether the patch mesh's floor has an element whose centre lies in the
// rectangle [x0, x1] x [z0, z1], or misses a vertex at one of its corners.
bool floor_covers(const patch_mesh& m, double x0, double x1, double z0, double z1) {
  for (std::size_t e = 0; e < m.element_count(); ++e) {
    if (m.element_surfaces[e] != 0) continue;
    vec3 c(0.0);
    for (int k = 0; k < 3; ++k) c += m.positions[m.elements[e][k]] / 3.0;
    if (c.x > x0 && c.x < x1 && c.z > z0 && c.z < z1) return true;
  }
  return false;
}
int floor_vertices_at(const patch_mesh& m, double x, double z) {
  int n = 0;
  for (std::size_t v = 0; v < m.vertex_count(); ++v)
    n += m.vertex_surfaces[v] == 0 && glm::length(m.positions[v] - vec3(x, 0, z)) < 1e-9 ? 1 : 0;
  return n;
}

TEST(ContactCut, ABoxOnTheFloorTakesItsFootprintOut) {
  for (const bool bottom : {true, false}) {  // a closed solid, or an open box turned over
    scene s = floor_under_a_lamp();
    add_solid_box(s, {-0.5, 0, -0.3}, {0.5, 0.8, 0.3}, 1, bottom);
    const floor_cut cut = cut_floor(s);
    EXPECT_EQ(cut.stats.footprints, 1u) << "bottom " << bottom;
    EXPECT_NEAR(cut.floor_area, 16.0 - 0.6, 1e-9) << "bottom " << bottom;
    EXPECT_NEAR(cut.mesh.contact_area_removed, 0.6, 1e-9);
    EXPECT_FALSE(floor_covers(cut.mesh, -0.5, 0.5, -0.3, 0.3));
    for (const double x : {-0.5, 0.5})
      for (const double z : {-0.3, 0.3}) EXPECT_EQ(floor_vertices_at(cut.mesh, x, z), 1) << x << ", " << z;
  }
}

TEST(ContactCut, WhatDoesNotTouchOrIsOpenAboveCutsNothing) {
  // Lifted by 1 cm (the lift is 1e-3 of the 6.4 m diagonal): not in contact.
  scene lifted = floor_under_a_lamp();
  add_solid_box(lifted, {-0.5, 0.01, -0.3}, {0.5, 0.8, 0.3}, 1);
  EXPECT_EQ(cut_floor(lifted).stats.footprints, 0u);
  EXPECT_NEAR(cut_floor(lifted).floor_area, 16.0, 1e-9);
  // A tube open at both ends: the floor inside it is seen from above.
  scene tube = floor_under_a_lamp();
  add_solid_box(tube, {-0.5, 0, -0.3}, {0.5, 0.8, 0.3}, 1, false, false);
  EXPECT_EQ(cut_floor(tube).stats.footprints, 0u);
  // A box standing beside the floor (outside its outline) leaves it whole.
  scene beside = floor_under_a_lamp();
  add_solid_box(beside, {2.5, 0, -0.3}, {3.5, 0.8, 0.3}, 1);
  EXPECT_NEAR(cut_floor(beside).floor_area, 16.0, 1e-9);
}

TEST(ContactCut, ATableCutsItsLegsNotTheGroundUnderItsTop) {
  scene s = floor_under_a_lamp();
  add_solid_box(s, {-1.0, 0.7, -0.6}, {1.0, 0.75, 0.6}, 1);  // the top
  for (const double x : {-0.95, 0.85})
    for (const double z : {-0.55, 0.45}) add_solid_box(s, {x, 0, z}, {x + 0.1, 0.7, z + 0.1}, 1);
  const floor_cut cut = cut_floor(s);
  // On the floor, and under the top where the legs meet it. The legs'
  // tops, inside the top, stay: the top overhangs them by more than their
  // own size (the search's reach; coplanar_cut.h).
  EXPECT_EQ(cut.stats.footprints, 4u + 4u);
  EXPECT_NEAR(cut.floor_area, 16.0 - 4 * 0.01, 1e-9);
  EXPECT_TRUE(floor_covers(cut.mesh, -0.8, 0.8, -0.4, 0.4));  // under the top, between the legs
}

TEST(ContactCut, TheCornellBoxFloorLosesTheBlocksFootprints) {
  // The official corners (the blocks stand on y = 0); the walls, which
  // stand on the floor's outline facing in, cut nothing.
  const scene s = load_embedded();
  auto shoelace = [](std::initializer_list<vec2> p) {
    const std::vector<vec2> c(p);
    double sum = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i)
      sum += c[i].x * c[(i + 1) % c.size()].y - c[(i + 1) % c.size()].x * c[i].y;
    return 0.5 * std::abs(sum);
  };
  const double footprints = shoelace({{130, 65}, {82, 225}, {240, 272}, {290, 114}}) +
                            shoelace({{423, 247}, {265, 296}, {314, 456}, {472, 406}});
  const patch_mesh mesh = test_support::mesh_of(s, 60.0);
  EXPECT_EQ(mesh.contact_footprints, 2u);
  EXPECT_NEAR(mesh.contact_area_removed, footprints, 1e-6 * footprints);
  const double whole_floor = area(tessellate(s.surfaces[std::size_t(surface_named(s, "floor"))], 60.0));
  EXPECT_NEAR(areas_by_surface(s, mesh)["floor"], whole_floor - footprints, 1e-6 * whole_floor);
}

TEST(DepthRange, ResolvesATenthOfAMillimetreAtTheBackOfTheCornellBox) {
  // 24-bit depth: points 0.1 mm apart along the view at the far end of the
  // light (z = 332) and at the back wall must land several depth steps
  // apart. With near = far / 1e4 (before) they were 0.3 steps apart.
  camera c;
  c.eye = vec3(278, 273, -800);
  c.target = vec3(278, 273, 0);
  c.fov_y_degrees = 39.3;
  const bounds3 box{vec3(0.0), vec3(556, 548.8, 559.2)};
  const glm::dmat4 clip = projection_matrix(c, box) * view_matrix(c);
  auto depth_steps = [&](const vec3& p) {
    auto window_z = [&](const vec3& q) {
      const glm::dvec4 h = clip * glm::dvec4(q, 1.0);
      return 0.5 * (h.z / h.w + 1.0);
    };
    const vec3 towards_eye = glm::normalize(c.eye - p);
    return (window_z(p) - window_z(p + 0.1 * towards_eye)) * double(1 << 24);
  };
  EXPECT_GT(depth_steps(vec3(213, 548.8, 332)), 4.0);
  EXPECT_GT(depth_steps(vec3(0, 548.8, 559.2)), 4.0);
  // Inside the box the near plane falls back to far / 1e4.
  c.eye = vec3(278, 273, 279);
  c.target = vec3(278, 273, 600);
  const glm::dmat4 inside = projection_matrix(c, box);
  const double near = inside[3][2] / (inside[2][2] - 1.0);
  EXPECT_GT(near, 0.0);
  EXPECT_LT(near, 1.0);
}

}  // namespace
}  // namespace bounce
