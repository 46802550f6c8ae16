// Conforming bisection of a built mesh (refine_patch_mesh) and adaptive
// meshing's a priori marks: conformity, area, what is marked.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "mesh/a_priori_refinement.h"
#include "mesh/patch_mesh.h"
#include "mesh_builders.h"
#include "mesh_checks.h"
#include "scene/scene_io.h"

namespace bounce {
namespace {

using test_support::add_closed_box;
using test_support::add_material;
using test_support::add_polygon;
using test_support::area_by_surface;
using test_support::furnace;
using test_support::hanging_vertices;
using test_support::load_ok;
using test_support::mesh_of;

TEST(Adaptive, TheConformityCheckSeesAHangingVertex) {
  // Two triangles of a square; one is split at the diagonal's midpoint and
  // the other is not: the midpoint hangs on the other's edge.
  patch_mesh mesh;
  mesh.scene_diagonal = 1.5;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  mesh.vertex_surfaces.assign(5, 0);
  mesh.elements = {{0, 1, 2}, {0, 4, 3}, {4, 2, 3}};
  mesh.element_surfaces.assign(3, 0);
  EXPECT_EQ(hanging_vertices(mesh), 1u);
  mesh.elements = {{0, 1, 4}, {4, 1, 2}, {0, 4, 3}, {4, 2, 3}};
  mesh.element_surfaces.assign(4, 0);
  EXPECT_EQ(hanging_vertices(mesh), 0u);
}

TEST(Adaptive, BisectionKeepsTheMeshConformingAndItsArea) {
  // The room alone: the blocks' footprints, cut out of the floor, leave
  // small single-element patches and the triangulation's narrower angles.
  scene s = load_ok(default_scene_path);
  std::erase_if(s.surfaces, [](const surface& surf) { return surf.name.find("block") != std::string::npos; });
  patch_mesh mesh = mesh_of(s, 120.0, 480.0);
  const auto area = area_by_surface(mesh);
  const std::size_t patches = mesh.patch_count();
  std::vector<int> marked;
  for (std::size_t e = 0; e < mesh.element_count(); e += 3) marked.push_back(int(e));
  std::vector<int> origin;
  std::string error;
  for (int pass = 0; pass < 4; ++pass) {
    const std::size_t before = mesh.element_count();
    ASSERT_TRUE(refine_patch_mesh(mesh, marked, 1.0, origin, error)) << error;
    EXPECT_GT(mesh.element_count(), before);
    ASSERT_EQ(origin.size(), mesh.element_count());
  }
  EXPECT_EQ(hanging_vertices(mesh), 0u);
  EXPECT_EQ(mesh.patch_count(), patches);  // patches of many elements stay
  for (const auto& [surface, a] : area_by_surface(mesh)) EXPECT_NEAR(a, area.at(surface), 1e-9 * a);
  // Every patch is still tiled exactly by its elements.
  std::vector<double> tiled(mesh.patch_count(), 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) tiled[mesh.element_patches[e]] += mesh.element_areas[e];
  for (std::size_t p = 0; p < mesh.patch_count(); ++p) EXPECT_NEAR(tiled[p], mesh.patch_areas[p], 1e-9 * tiled[p]);
  // Longest-edge bisection keeps angles bounded: no sliver appears.
  double smallest = 180.0;
  for (const glm::ivec3& t : mesh.elements)
    for (int k = 0; k < 3; ++k) {
      const vec3 u = glm::normalize(mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]);
      const vec3 w = glm::normalize(mesh.positions[t[(k + 2) % 3]] - mesh.positions[t[k]]);
      smallest = std::min(smallest, glm::degrees(std::acos(std::clamp(glm::dot(u, w), -1.0, 1.0))));
    }
  EXPECT_GT(smallest, 5.0);
}

TEST(Adaptive, RepeatedBisectionInOneCallStaysConformingAndLeavesOtherSurfacesAlone) {
  const scene s = load_ok(default_scene_path);
  const patch_mesh before = mesh_of(s, 120.0, 480.0);
  patch_mesh mesh = before;
  const std::vector<int> marked = {0, int(before.element_count() / 2)};
  const std::vector<int> times = {4, 2};
  std::vector<int> origin;
  std::string error;
  ASSERT_TRUE(refine_patch_mesh(mesh, marked, 1.0, origin, error, times)) << error;
  ASSERT_EQ(origin.size(), mesh.element_count());
  EXPECT_EQ(hanging_vertices(mesh), 0u);
  // Each round splits every piece still asking once: at least 2^times pieces.
  for (std::size_t i = 0; i < marked.size(); ++i) {
    std::size_t pieces = 0;
    double area = 0.0;
    for (std::size_t e = 0; e < mesh.element_count(); ++e)
      if (origin[e] == marked[i]) {
        ++pieces;
        area += mesh.element_areas[e];
      }
    EXPECT_GE(pieces, std::size_t(1) << times[i]) << i;
    EXPECT_NEAR(area, before.element_areas[std::size_t(marked[i])], 1e-9 * area) << i;
  }
  // Surfaces without a mark keep their elements exactly.
  std::set<int> touched;
  for (int e : marked) touched.insert(before.element_surfaces[std::size_t(e)]);
  std::size_t kept = 0, expected = 0;
  for (std::size_t e = 0; e < before.element_count(); ++e)
    expected += touched.count(before.element_surfaces[e]) ? 0 : 1;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const int o = origin[e];
    if (touched.count(before.element_surfaces[std::size_t(o)])) continue;
    ASSERT_EQ(mesh.elements[e], before.elements[std::size_t(o)]);
    ++kept;
  }
  EXPECT_EQ(kept, expected);
}

TEST(Adaptive, APrioriMarksContactsAndElementsNearEmitters) {
  // Cornell box: contacts are the blocks' feet only (the floor and the
  // blocks), never the walls, whose boundaries meet the floor's.
  const scene cornell = load_ok(default_scene_path);
  const patch_mesh mesh = mesh_of(cornell, 100.0, 400.0);
  const std::vector<int> contacts = contact_marks(mesh, 10.0);
  ASSERT_FALSE(contacts.empty());
  for (int e : contacts) {
    const std::string& name = cornell.surfaces[mesh.element_surfaces[e]].name;
    EXPECT_TRUE(name.find("floor") != std::string::npos || name.find("block") != std::string::npos) << name;
  }
  // A small emitter 5 cm above a 1 m floor, facing it: the floor under it is
  // marked, the far floor is not; nothing behind the emitter is.
  scene s;
  const int grey = add_material(s, rgb(0.5));
  const int light = add_material(s, rgb(0.0), rgb(1.0));
  add_polygon(s, {{-0.5, 0, -0.5}, {-0.5, 0, 0.5}, {0.5, 0, 0.5}, {0.5, 0, -0.5}}, grey);
  add_polygon(s, {{-0.05, 0.05, -0.05}, {0.05, 0.05, -0.05}, {0.05, 0.05, 0.05}, {-0.05, 0.05, 0.05}}, light);
  const patch_mesh lit = mesh_of(s, 0.1, 0.1);
  const std::vector<int> near = emitter_marks(lit, 0.01);
  ASSERT_FALSE(near.empty());
  for (int e : near) {
    const glm::ivec3 t = lit.elements[e];
    const vec3 c = (lit.positions[t[0]] + lit.positions[t[1]] + lit.positions[t[2]]) / 3.0;
    EXPECT_LT(glm::length(vec3(c.x, 0.0, c.z)), 0.25) << "marked far from the emitter";
  }
  patch_mesh refined = lit;
  refinement_pass report;
  std::string error;
  ASSERT_TRUE(refine_a_priori(refined, 0.01, report, error)) << error;
  EXPECT_GT(report.emitter, 0u);
  EXPECT_GT(refined.element_count(), lit.element_count());
  EXPECT_TRUE(emitter_marks(refined, 0.01).empty());  // refined until nothing is marked
}

}  // namespace
}  // namespace bounce
