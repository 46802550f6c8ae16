// The hierarchical solver against exact answers, the element-level
// solution it converges to, and how its steps refine and publish.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <chrono>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "radiosity/hierarchical/diagnostics.h"
#include "radiosity/hierarchical/fixtures.h"
#include "radiosity/hierarchical/solver.h"
#include "radiosity/solver.h"
#include "radiosity/transfer/form_factor.h"

namespace bounce {
namespace {

using std::numbers::pi;
using namespace test_support;  // the fixtures: hierarchical(), solve(), cornell(), ...

TEST(Hierarchical, FurnaceIsExactAtHighReflectance) {
  for (double rho : {0.5, 0.99, 0.999}) {
    const scene s = furnace(rho);
    const patch_mesh mesh = mesh_of(s, 0.25);
    auto solver = make_radiosity_solver(s, mesh, hierarchical(1e-4));
    solve(*solver, 1e-9, 200);
    ASSERT_TRUE(hierarchical_of(*solver)->progress.closed);
    const double exact = pi / (1.0 - rho);
    const auto solution = make_snapshot(*solver);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
      ASSERT_NEAR(solution->radiosity[v].g, exact, 1e-7 * exact) << "rho " << rho << " vertex " << v;
    // Krylov iterations: a few dozen operator applications even at 0.999
    // (Jacobi would need thousands).
    EXPECT_LT(hierarchical_of(*solver)->progress.operator_applications, 150u) << "rho " << rho;
  }
}

TEST(Hierarchical, ConvergesToTheElementLevelSolutionAsTheToleranceFalls) {
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 150.0);
  ASSERT_LT(mesh.element_count(), 1500u);
  double previous = INFINITY;
  for (double tolerance : {1e-3, 1e-5, 1e-12}) {
    auto solver = make_radiosity_solver(s, mesh, hierarchical(tolerance));
    solve(*solver, 1e-12);
    const hierarchical_solver& h = *hierarchical_of(*solver);
    const double difference = largest_relative_difference(h.light.total, element_level_solution(h));
    EXPECT_LT(difference, previous) << "tolerance " << tolerance;
    previous = difference;
    if (tolerance == 1e-12) {
      EXPECT_LT(difference, 1e-6);
      // Every link is element to element at tolerance 0.
      for (const hierarchy_link& link : h.hierarchy.links.links) {
        ASSERT_TRUE(h.hierarchy.tree.nodes[link.receiver].leaf());
        ASSERT_TRUE(h.hierarchy.tree.nodes[link.source].leaf());
      }
    }
  }
}

TEST(Hierarchical, ManySmallCoplanarTrianglesReceiveWhatTheirPolygonDoes) {
  // An emitter over a 1 x 1 floor made of a 40 x 40 grid of separate
  // quads (3,200 triangles, one surface each), which the tree clusters.
  scene s;
  const int light = add_material(s, rgb(0.0), rgb(10.0));
  const int white = add_material(s, rgb(0.5));
  const std::vector<vec3> emitter = {{-0.2, 1.5, -0.2}, {0.2, 1.5, -0.2}, {0.2, 1.5, 0.2}, {-0.2, 1.5, 0.2}};
  add_polygon(s, emitter, light);
  const int cells = 40;
  const double step = 1.0 / cells;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const double x = -0.5 + i * step, z = -0.5 + j * step;
      add_polygon(s, {{x, 0, z}, {x, 0, z + step}, {x + step, 0, z + step}, {x + step, 0, z}}, white);
    }
  const patch_mesh mesh = mesh_of(s, 10.0);
  ASSERT_EQ(mesh.element_count(), 2u + 2u * cells * cells);
  auto solver = make_radiosity_solver(s, mesh, hierarchical(1e-3));
  solve(*solver, 1e-9);
  const hierarchical_solver& h = *hierarchical_of(*solver);
  ASSERT_EQ(h.gathered.total.size(), mesh.vertex_count());
  const double reflected = integral_over_elements(mesh, h.gathered.total).g;
  // What the floor as one polygon receives: Lambert's formula integrated
  // over it (midpoint rule on a 200 x 200 grid, far finer than needed).
  const double exitance = pi * 10.0;
  double exact = 0.0;
  const int n = 200;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const vec3 p(-0.5 + (i + 0.5) / n, 0.0, -0.5 + (j + 0.5) / n);
      exact += point_polygon_form_factor(p, vec3(0, 1, 0), emitter) / (n * n);
    }
  exact *= 0.5 * exitance;
  EXPECT_NEAR(reflected / exact, 1.0, 0.01);
  // The grid is reached through clusters, not element by element.
  EXPECT_LT(h.hierarchy.links.size(), std::size_t(cells * cells));
}

TEST(Hierarchical, PointLightGivesTheInverseSquareLawAtElementCentres) {
  scene s;
  const int white = add_material(s, rgb(0.5));
  add_polygon(s, {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}, white);
  s.lights.push_back({vec3(0.3, 2, 0.1), rgb(10, 20, 30)});
  const patch_mesh mesh = mesh_of(s, 0.5);
  auto solver = make_radiosity_solver(s, mesh, hierarchical(1e-5));
  solve(*solver, 1e-12);
  const hierarchical_solver& h = *hierarchical_of(*solver);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const vec3 d = s.lights[0].position - h.hierarchy.tree.nodes[h.hierarchy.tree.leaf_of_element[e]].centroid;
    EXPECT_NEAR(h.light.total[e].b, 0.5 * 30 * d.y / std::pow(glm::length(d), 3.0), 1e-12);
    EXPECT_EQ(h.light.direct[e], h.light.total[e]);
  }
}

TEST(Hierarchical, RefinesBetweenIterationsAndPublishesEveryStep) {
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 40.0);
  auto solver = make_radiosity_solver(s, mesh, hierarchical(1e-5));
  std::size_t links = 0;
  double tolerance = INFINITY;
  int refinements = 0;
  for (int step = 0; step < 200 && step_solver(*solver); ++step) {
    // Every step publishes vertex radiosity for the view.
    ASSERT_EQ(make_snapshot(*solver)->radiosity.size(), mesh.vertex_count());
    const hierarchical_solver& h = *hierarchical_of(*solver);
    if (h.progress.tolerance < tolerance) {
      EXPECT_GE(h.hierarchy.links.size(), links);  // links are only ever split
      links = h.hierarchy.links.size();
      tolerance = h.progress.tolerance;
      ++refinements;
    }
    if (solver->stats.remaining_final && solver->stats.remaining < 1e-6) break;
  }
  EXPECT_EQ(refinements, 4);  // the first links and three refinements
  EXPECT_DOUBLE_EQ(tolerance, 1e-5);
  EXPECT_LT(solver->stats.remaining, 1e-6);
}

// A time limit holds within a step: a link refinement running past the
// deadline splits no more pairs and keeps the links it has as they are.
// With the deadline past before every step, the first links are the
// root's children's pairs, and no later refinement splits one of them.
// (At link tolerance 1e-9 one refinement of the Cornell box took 21 s
// here; with a 5 s limit the run now ends after 5.4 s.)
TEST(Hierarchical, ATimeLimitCutsALinkRefinementShort) {
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 40.0);
  auto solver = make_radiosity_solver(s, mesh, hierarchical(1e-9));
  const auto past = std::chrono::steady_clock::time_point::min();
  ASSERT_TRUE(step_solver(*solver, past));
  const hierarchical_solver& h = *hierarchical_of(*solver);
  const std::size_t first = h.hierarchy.links.size();
  EXPECT_TRUE(solver->stats.cut_short);
  for (int step = 0; step < 30 && step_solver(*solver, past); ++step) {
    ASSERT_EQ(h.hierarchy.links.size(), first) << "step " << step;
    EXPECT_FALSE(h.progress.links_final);
  }
  EXPECT_GE(h.progress.refinements, 3);
  EXPECT_TRUE(solver->stats.cut_short);
  EXPECT_FALSE(solver->stats.remaining_final);
  const auto solution = make_snapshot(*solver);
  for (const rgb& b : solution->radiosity)
    for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(b[c]) && b[c] >= 0.0) << b[c];
}

// Cut short at once (a deadline already past), the first links are the
// root's; stepping on without a limit refines them again at every
// tolerance and reaches the solution of a run never cut short.
TEST(Hierarchical, ARunCutShortRefinesAgainWhenItGoesOn) {
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 40.0);
  auto whole = make_radiosity_solver(s, mesh, hierarchical(1e-5));
  solve(*whole, 1e-6);
  auto cut = make_radiosity_solver(s, mesh, hierarchical(1e-5));
  ASSERT_TRUE(step_solver(*cut, std::chrono::steady_clock::time_point::min()));
  EXPECT_TRUE(cut->stats.cut_short);
  const std::size_t first_links = hierarchical_of(*cut)->hierarchy.links.size();
  EXPECT_LT(first_links, hierarchical_of(*whole)->hierarchy.links.size() / 10);
  solve(*cut, 1e-6);
  EXPECT_FALSE(cut->stats.cut_short);
  EXPECT_TRUE(hierarchical_of(*cut)->progress.links_final);
  EXPECT_GT(hierarchical_of(*cut)->hierarchy.links.size(), 10 * first_links);
  const auto a = make_snapshot(*cut)->radiosity, b = make_snapshot(*whole)->radiosity;
  EXPECT_LT(integral_over_elements(mesh, a).g / integral_over_elements(mesh, b).g - 1.0, 0.01);
  EXPECT_GT(integral_over_elements(mesh, a).g / integral_over_elements(mesh, b).g - 1.0, -0.01);
}

TEST(Hierarchical, ParallelAndSerialRunsAgree) {
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 60.0);
  radiosity_params serial = hierarchical(1e-5);
  serial.hierarchical.parallel = false;
  auto a = make_radiosity_solver(s, mesh, serial);
  auto b = make_radiosity_solver(s, mesh, hierarchical(1e-5));
  solve(*a, 1e-6);
  solve(*b, 1e-6);
  ASSERT_EQ(hierarchical_of(*a)->hierarchy.links.size(), hierarchical_of(*b)->hierarchy.links.size());
  EXPECT_LT(largest_relative_difference(make_snapshot(*a)->radiosity, make_snapshot(*b)->radiosity), 1e-12);
}

}  // namespace
}  // namespace bounce
