// The progressive solver's a posteriori refinement: the solution carried
// exactly to new vertices, conformity and area kept, and where refinement
// goes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh_builders.h"
#include "mesh_checks.h"
#include "progressive_runs.h"
#include "radiosity/progressive/adaptive_refinement.h"
#include "radiosity/progressive/progressive.h"
#include "radiosity/progressive/reference_solver.h"
#include "radiosity/solver.h"
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
using test_support::run_until;

progressive_params adaptive(double tolerance) {
  progressive_params p;
  p.adaptive.enabled = true;
  p.adaptive.tolerance = tolerance;
  return p;
}

TEST(Adaptive, SolvedCornellMeshIsConformingWithItsAreaKept) {
  const scene s = load_ok(default_scene_path);
  const patch_mesh mesh = mesh_of(s, 150.0, 600.0, default_min_edge(150.0));
  auto state = make_progressive_state(s, mesh, adaptive(0.15));
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
  auto state = make_progressive_state(s, mesh, {});
  run_until(*state, 0.3);
  std::vector<int> marked;
  for (std::size_t e = 0; e < mesh.element_count(); e += 3) marked.push_back(int(e));
  std::string error;
  std::size_t added = 0;
  ASSERT_TRUE(refine_progressive(*state, marked, 0.01, error, &added)) << error;
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
  auto state = make_progressive_state(s, mesh, {});
  run_until(*state, 0.2);
  std::vector<int> marked;
  for (std::size_t e = 0; e < mesh.element_count(); e += 2) marked.push_back(int(e));
  std::string error;
  ASSERT_TRUE(refine_progressive(*state, marked, 0.01, error)) << error;
  ASSERT_TRUE(refine_progressive(*state, marked, 0.01, error)) << error;
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
  auto state = make_progressive_state(s, mesh, {});
  ASSERT_TRUE(step_progressive(*state));  // the point light first
  std::vector<int> marked;
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    if (mesh.element_surfaces[e] == 0) marked.push_back(int(e));
  std::string error;
  std::size_t added = 0;
  ASSERT_TRUE(refine_progressive(*state, marked, 0.01, error, &added)) << error;
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
  auto state = make_progressive_state(s, mesh, adaptive(0.15));
  run_until(*state, 1e-3);
  EXPECT_EQ(state->mesh->element_count(), mesh.element_count());
  EXPECT_EQ(state->stats.refinements, 0u);
  ASSERT_FALSE(state->adaptive.history.empty());  // a pass ran and found nothing to split
  EXPECT_EQ(state->adaptive.history[0].gradient, 0u);
  EXPECT_EQ(state->adaptive.history[0].shadow, 0u);
  EXPECT_TRUE(state->adaptive.finished);
}

TEST(Adaptive, RefinementConcentratesAlongTheBlocksShadowEdges) {
  const scene s = load_ok(default_scene_path);
  const patch_mesh mesh = mesh_of(s, 100.0, 0.0, default_min_edge(100.0));  // as --adaptive: elements shoot
  auto state = make_progressive_state(s, mesh, adaptive(0.5));
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

TEST(Adaptive, SnapshotsBelongToTheRefinedMesh) {
  const scene s = load_ok(default_scene_path);
  const patch_mesh mesh = mesh_of(s, 150.0, 600.0);
  radiosity_params params;
  params.adaptive = adaptive(0.15).adaptive;
  auto solver = make_radiosity_solver(s, mesh, params);
  EXPECT_EQ(make_snapshot(*solver)->radiosity.size(), mesh.vertex_count());
  stop_criterion stop;
  stop.remaining = 0.05;
  run_solver(*solver, stop);
  ASSERT_GT(solver->stats.refinements, 0u);
  ASSERT_NE(&solved_mesh(*solver), &mesh);
  const auto snapshot = make_snapshot(*solver);
  EXPECT_EQ(snapshot->radiosity.size(), solved_mesh(*solver).vertex_count());
  EXPECT_GT(snapshot->radiosity.size(), mesh.vertex_count());
  EXPECT_EQ(snapshot->version, solver->stats.steps + solver->stats.refinements);
}

}  // namespace
}  // namespace bounce
