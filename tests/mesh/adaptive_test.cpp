// Adaptive meshing: conformity, area, exact bookkeeping of the solution
// carried to new vertices, and where refinement goes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "mesh/adaptive.h"
#include "mesh/patch_mesh.h"
#include "mesh_builders.h"
#include "radiosity/radiosity.h"
#include "radiosity/reference_solver.h"
#include "scene/scene_io.h"

namespace bounce {
namespace {

using test_support::add_closed_box;
using test_support::add_material;
using test_support::add_polygon;
using test_support::furnace;

scene load(const std::string& path) {
  scene s;
  load_report report;
  EXPECT_TRUE(load_scene(path, s, report)) << report.error;
  return s;
}

patch_mesh mesh_of(const scene& s, double max_edge, double patch_edge, double a_priori_min_edge = 0.0) {
  mesher_params params;
  params.max_edge = max_edge;
  params.patch_edge = patch_edge;
  params.a_priori_min_edge = a_priori_min_edge;
  patch_mesh mesh;
  std::string error;
  EXPECT_TRUE(make_patch_mesh(s, params, mesh, error)) << error;
  return mesh;
}

void run_until(radiosity_state& state, double fraction) {
  stop_criterion stop;
  stop.unshot_fraction = fraction;
  run_radiosity(state, stop, [](const radiosity_state&) {});
}

radiosity_params adaptive(double tolerance) {
  radiosity_params p;
  p.adaptive.enabled = true;
  p.adaptive.tolerance = tolerance;
  return p;
}

// Connected pieces of the mesh (vertices linked by elements): a smooth
// piece of a surface. Creases and material changes split vertices, so the
// faces of a box are pieces of their own.
std::vector<int> pieces(const patch_mesh& mesh) {
  std::vector<int> parent(mesh.vertex_count());
  for (std::size_t v = 0; v < parent.size(); ++v) parent[v] = int(v);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const glm::ivec3& t : mesh.elements) {
    parent[find(t[1])] = find(t[0]);
    parent[find(t[2])] = find(t[0]);
  }
  for (std::size_t v = 0; v < parent.size(); ++v) parent[v] = find(int(v));
  return parent;
}

// Vertices lying strictly inside another element's edge of the same smooth
// piece: T-vertices, the cracks of a non-conforming mesh.
std::size_t hanging_vertices(const patch_mesh& mesh) {
  const std::vector<int> piece = pieces(mesh);
  std::map<int, std::vector<int>> by_piece;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) by_piece[piece[v]].push_back(int(v));
  std::size_t hanging = 0;
  const double tolerance = 1e-9 * mesh.scene_diagonal;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    for (int k = 0; k < 3; ++k) {
      const vec3 a = mesh.positions[t[k]], b = mesh.positions[t[(k + 1) % 3]];
      const double length2 = glm::dot(b - a, b - a);
      for (int v : by_piece[piece[t[0]]]) {
        if (v == t[0] || v == t[1] || v == t[2]) continue;
        const vec3 p = mesh.positions[v];
        const double s = glm::dot(p - a, b - a) / length2;
        if (s <= 1e-9 || s >= 1.0 - 1e-9) continue;
        if (glm::length(p - (a + (b - a) * s)) < tolerance) ++hanging;
      }
    }
  }
  return hanging;
}

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

std::map<int, double> area_by_surface(const patch_mesh& mesh) {
  std::map<int, double> area;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) area[mesh.element_surfaces[e]] += mesh.element_areas[e];
  return area;
}

TEST(Adaptive, BisectionKeepsTheMeshConformingAndItsArea) {
  const scene s = load(default_scene_path);
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
  const scene s = load(default_scene_path);
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

TEST(Adaptive, SolvedCornellMeshIsConformingWithItsAreaKept) {
  const scene s = load(default_scene_path);
  const patch_mesh mesh = mesh_of(s, 150.0, 600.0, default_min_edge(150.0));
  auto state = make_radiosity_state(s, mesh, adaptive(0.15));
  run_until(*state, 0.01);
  ASSERT_GT(state->stats.refinements, 0u);
  const patch_mesh& refined = *state->mesh;
  EXPECT_GT(refined.element_count(), mesh.element_count());
  EXPECT_EQ(hanging_vertices(refined), 0u);
  const auto before = area_by_surface(mesh);
  for (const auto& [surface, a] : area_by_surface(refined)) EXPECT_NEAR(a, before.at(surface), 1e-9 * a);
  EXPECT_LT(balance_error(state->balance), 1e-12);
  // Nothing below the minimum edge was split: every element's longest edge
  // is at least half of it.
  for (const glm::ivec3& t : refined.elements) {
    double longest = 0.0;
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, glm::length(refined.positions[t[(k + 1) % 3]] - refined.positions[t[k]]));
    EXPECT_GE(longest, 0.5 * default_min_edge(150.0) - 1e-9);
  }
}

TEST(Adaptive, RefinedFurnaceIsStillExact) {
  // Refine a third of the elements part-way through the solve: the new
  // vertices gather every shot made, and the answer stays E / (1 - rho).
  const double rho = 0.5;
  const scene s = furnace(rho);
  const patch_mesh mesh = mesh_of(s, 0.5, 1.0);
  auto state = make_radiosity_state(s, mesh, {});
  run_until(*state, 0.3);
  std::vector<int> marked;
  for (std::size_t e = 0; e < mesh.element_count(); e += 3) marked.push_back(int(e));
  std::string error;
  std::size_t added = 0;
  ASSERT_TRUE(refine_radiosity(*state, marked, 0.01, error, &added)) << error;
  EXPECT_GT(added, 0u);
  EXPECT_LT(balance_error(state->balance), 1e-12);
  run_until(*state, 1e-4);
  const double exact = 1.0 * std::numbers::pi / (1.0 - rho);  // E = pi ke
  double worst = 0.0;
  for (const rgb& b : state->radiosity) worst = std::max(worst, std::abs(b.g / exact - 1.0));
  EXPECT_LT(worst, 2e-3);
  EXPECT_LT(balance_error(state->balance), 1e-12);
}

TEST(Adaptive, ConvergesToTheReferenceSolutionOnTheRefinedMesh) {
  // An empty box lit from one face: no occlusion, so form factors are
  // analytic and additive over a split, and with element shooters the
  // progressive solution on the refined mesh must be the matrix solution
  // on that mesh.
  scene s;
  const int white = add_material(s, rgb(0.6, 0.5, 0.4));
  const int light = add_material(s, rgb(0.3), rgb(2.0));
  add_closed_box(s, vec3(0.0), vec3(1.0), white);
  std::get<polygon_mesh>(s.surfaces[5].geometry).faces[0].material = light;
  const patch_mesh mesh = mesh_of(s, 0.5, 0.0);
  auto state = make_radiosity_state(s, mesh, {});
  run_until(*state, 0.2);
  std::vector<int> marked;
  for (std::size_t e = 0; e < mesh.element_count(); e += 2) marked.push_back(int(e));
  std::string error;
  ASSERT_TRUE(refine_radiosity(*state, marked, 0.01, error)) << error;
  ASSERT_TRUE(refine_radiosity(*state, marked, 0.01, error)) << error;
  const patch_mesh& refined = *state->mesh;
  EXPECT_EQ(refined.patch_count(), refined.element_count());  // element shooters stay element shooters
  run_until(*state, 1e-12);
  reference_params params;
  reference_solution reference;
  ASSERT_TRUE(solve_reference(s, refined, params, reference, error)) << error;
  double worst = 0.0;
  for (std::size_t v = 0; v < refined.vertex_count(); ++v)
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(state->radiosity[v][c] / reference.radiosity[v][c] - 1.0));
  EXPECT_LT(worst, 1e-9);
}

TEST(Adaptive, NewVerticesGetThePointLightsDirectLight) {
  // A floor under a point light (and facing a dim emitter so there is
  // something to shoot): after refining, every vertex, new or old, holds the
  // light's exact direct term rho I cos / r^2.
  scene s;
  const int grey = add_material(s, rgb(0.5));
  const int glow = add_material(s, rgb(0.0), rgb(0.01));
  add_polygon(s, {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}, grey);
  add_polygon(s, {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}}, glow);
  s.lights.push_back({vec3(0.3, 1.0, -0.2), rgb(2.0)});
  const patch_mesh mesh = mesh_of(s, 0.5, 0.0);
  auto state = make_radiosity_state(s, mesh, {});
  ASSERT_TRUE(step_radiosity(*state));  // the point light first
  std::vector<int> marked;
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    if (mesh.element_surfaces[e] == 0) marked.push_back(int(e));
  std::string error;
  std::size_t added = 0;
  ASSERT_TRUE(refine_radiosity(*state, marked, 0.01, error, &added)) << error;
  ASSERT_GT(added, 0u);
  const patch_mesh& refined = *state->mesh;
  for (std::size_t v = 0; v < refined.vertex_count(); ++v) {
    if (refined.vertex_surfaces[v] != 0) continue;
    const vec3 to_light = s.lights[0].position - refined.receive_points[v];
    const double r2 = glm::dot(to_light, to_light);
    const double exact = 0.5 * 2.0 * (to_light.y / std::sqrt(r2)) / r2;
    EXPECT_NEAR(state->direct[v].g, exact, 1e-12 * exact) << v;
    EXPECT_NEAR(state->radiosity[v].g, exact, 1e-12 * exact) << v;
  }
  EXPECT_LT(balance_error(state->balance), 1e-12);
}

TEST(Adaptive, UniformLightWithoutShadowsDoesNotRefine) {
  const scene s = furnace(0.5);
  const patch_mesh mesh = mesh_of(s, 0.5, 1.0, default_min_edge(0.5));
  auto state = make_radiosity_state(s, mesh, adaptive(0.15));
  run_until(*state, 1e-3);
  EXPECT_EQ(state->mesh->element_count(), mesh.element_count());
  EXPECT_EQ(state->stats.refinements, 0u);
  ASSERT_FALSE(state->adaptive.history.empty());  // a pass ran and found nothing to split
  EXPECT_EQ(state->adaptive.history[0].gradient, 0u);
  EXPECT_EQ(state->adaptive.history[0].shadow, 0u);
  EXPECT_TRUE(state->adaptive.finished);
}

TEST(Adaptive, RefinementConcentratesAlongTheBlocksShadowEdges) {
  const scene s = load(default_scene_path);
  const patch_mesh mesh = mesh_of(s, 100.0, 0.0, default_min_edge(100.0));  // as --adaptive: elements shoot
  auto state = make_radiosity_state(s, mesh, adaptive(0.5));
  run_until(*state, 0.01);
  const patch_mesh& refined = *state->mesh;
  auto surface_named = [&](const std::string& part) {
    std::vector<int> ids;
    for (std::size_t i = 0; i < s.surfaces.size(); ++i)
      if (s.surfaces[i].name.find(part) != std::string::npos) ids.push_back(int(i));
    return ids;
  };
  const std::vector<int> floor = surface_named("floor"), ceiling = surface_named("ceiling");
  const std::vector<int> blocks = surface_named("block");
  ASSERT_EQ(floor.size(), 1u);
  ASSERT_EQ(ceiling.size(), 1u);
  ASSERT_EQ(blocks.size(), 2u);
  // The blocks' feet: their edges on the floor (y = 0).
  std::vector<std::pair<vec3, vec3>> feet;
  for (std::size_t e = 0; e < refined.element_count(); ++e) {
    if (std::find(blocks.begin(), blocks.end(), refined.element_surfaces[e]) == blocks.end()) continue;
    const glm::ivec3 t = refined.elements[e];
    for (int k = 0; k < 3; ++k) {
      const vec3 a = refined.positions[t[k]], b = refined.positions[t[(k + 1) % 3]];
      if (std::abs(a.y) < 1e-9 && std::abs(b.y) < 1e-9) feet.emplace_back(a, b);
    }
  }
  ASSERT_FALSE(feet.empty());
  auto distance_to_feet = [&](const vec3& p) {
    double best = std::numeric_limits<double>::max();
    for (const auto& [a, b] : feet) {
      const double t = std::clamp(glm::dot(p - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
      best = std::min(best, glm::length(p - (a + (b - a) * t)));
    }
    return best;
  };
  // Elements per area: on the floor within 30 mm of a foot, and on the
  // ceiling away from the light (farther than 150 mm from its centre).
  double near_area = 0.0, open_area = 0.0;
  std::size_t near_count = 0, open_count = 0;
  for (std::size_t e = 0; e < refined.element_count(); ++e) {
    const glm::ivec3 t = refined.elements[e];
    const vec3 c = (refined.positions[t[0]] + refined.positions[t[1]] + refined.positions[t[2]]) / 3.0;
    if (refined.element_surfaces[e] == floor[0] && distance_to_feet(c) < 30.0) {
      near_area += refined.element_areas[e];
      ++near_count;
    } else if (refined.element_surfaces[e] == ceiling[0] && glm::length(vec3(c.x - 278.0, 0.0, c.z - 279.5)) > 150.0) {
      open_area += refined.element_areas[e];
      ++open_count;
    }
  }
  ASSERT_GT(near_count, 0u);
  ASSERT_GT(open_count, 0u);
  const double near_density = near_count / near_area, open_density = open_count / open_area;
  EXPECT_GT(near_density, 8.0 * open_density) << near_density << " vs " << open_density;
}

TEST(Adaptive, APrioriMarksContactsAndElementsNearEmitters) {
  // Cornell box: contacts are the blocks' feet only (the floor and the
  // blocks), never the walls, whose boundaries meet the floor's.
  const scene cornell = load(default_scene_path);
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

TEST(Adaptive, SnapshotsBelongToTheRefinedMesh) {
  const scene s = load(default_scene_path);
  const patch_mesh mesh = mesh_of(s, 150.0, 600.0);
  auto state = make_radiosity_state(s, mesh, adaptive(0.15));
  EXPECT_EQ(make_snapshot(*state)->radiosity.size(), mesh.vertex_count());
  run_until(*state, 0.05);
  ASSERT_GT(state->stats.refinements, 0u);
  ASSERT_NE(state->mesh, &mesh);
  const auto snapshot = make_snapshot(*state);
  EXPECT_EQ(snapshot->radiosity.size(), state->mesh->vertex_count());
  EXPECT_GT(snapshot->radiosity.size(), mesh.vertex_count());
  EXPECT_EQ(snapshot->version, state->stats.shots + state->stats.refinements);
}

}  // namespace
}  // namespace bounce
