// Importance from the camera: two closed rooms side by side, each with its
// own lamp. Led by a view inside one, the solver refines that room as far
// as the view-independent solve does and leaves the other coarse; a new
// view keeps what was refined and refines what it sees.
#include <gtest/gtest.h>

#include "radiosity/hierarchical/fixtures.h"
#include "radiosity/hierarchical/publication.h"
#include "radiosity/hierarchical/solver.h"
#include "radiosity/hierarchical/view_importance.h"
#include "radiosity/solve.h"

namespace bounce {
namespace {

using namespace test_support;

// Rooms [-3, -1] and [1, 3] along x (2 x 2 x 2 each), a lamp under each
// ceiling; the scene's camera stands in the left one.
scene two_rooms() {
  scene s;
  const int wall = add_material(s, rgb(0.6));
  const int lamp = add_material(s, rgb(0.0), rgb(5.0));
  for (const double x0 : {-3.0, 1.0}) {
    add_closed_box(s, vec3(x0, -1.0, -1.0), vec3(x0 + 2.0, 1.0, 1.0), wall);
    add_polygon(
        s,
        {vec3(x0 + 0.7, 0.99, -0.3), vec3(x0 + 1.3, 0.99, -0.3), vec3(x0 + 1.3, 0.99, 0.3), vec3(x0 + 0.7, 0.99, 0.3)},
        lamp, "lamp");
  }
  s.view.eye = vec3(-2.0, 0.0, 0.9);
  s.view.target = vec3(-2.0, -0.3, -1.0);
  s.view.width = s.view.height = 64;
  return s;
}

camera in_right_room(const scene& s) {
  camera c = s.view;
  c.eye.x += 4.0;
  c.target.x += 4.0;
  return c;
}

// Links whose receiver lies in the left room (centroid x < 0) and in the right one.
struct links_by_room {
  std::size_t left = 0, right = 0;
};

links_by_room count_links(const radiosity_solver& solver) {
  const hierarchical_solver& h = *hierarchical_of(solver);
  links_by_room out;
  for (const hierarchy_link& link : h.hierarchy.links.links) {
    const cluster_node& r = h.hierarchy.tree.nodes[std::size_t(link.receiver)];
    if (r.hi.x < 0.0) ++out.left;
    if (r.lo.x > 0.0) ++out.right;
  }
  return out;
}

std::unique_ptr<radiosity_solver> solved(const scene& s, solve_setup& setup, bool led) {
  solver_settings settings;
  settings.link_tolerance = 2e-5;
  if (led) settings.view = s.view;
  std::string error;
  EXPECT_TRUE(start_solve(s, settings, setup, error)) << error;
  solve(*setup.solver, 1e-4);
  return std::move(setup.solver);
}

TEST(ViewImportance, TheRoomInViewIsRefinedAndTheOtherIsNot) {
  const scene s = two_rooms();
  solve_setup plain_setup, led_setup;
  const auto plain = solved(s, plain_setup, false);
  const auto led = solved(s, led_setup, true);
  const links_by_room a = count_links(*plain), b = count_links(*led);
  // Without a view the two rooms are mirror images: alike.
  EXPECT_NEAR(double(a.left), double(a.right), 0.1 * double(a.left));
  EXPECT_GE(double(b.left), 0.9 * double(a.left));
  EXPECT_LT(double(b.right), 0.5 * double(a.right)) << "unseen room: " << b.right << " of " << a.right;
  const hierarchical_solver& h = *hierarchical_of(*led);
  ASSERT_FALSE(h.view.node.empty());
  // The seen room's elements weigh more than 1, the unseen room's far less.
  double seen = 0.0, unseen = 0.0, seen_area = 0.0, unseen_area = 0.0;
  for (std::size_t e = 0; e < h.mesh().element_count(); ++e) {
    const double w = receiver_weight(h, h.hierarchy.tree.leaf_of_element[e]);
    const double area = h.mesh().element_areas[e];
    (element_centroid(h.mesh(), e).x < 0.0 ? seen : unseen) += w * area;
    (element_centroid(h.mesh(), e).x < 0.0 ? seen_area : unseen_area) += area;
  }
  EXPECT_GT(seen / seen_area, 1.0);
  EXPECT_LT(unseen / unseen_area, 0.1 * seen / seen_area);
}

TEST(ViewImportance, ANewViewKeepsWhatWasRefinedAndRefinesWhatItSees) {
  const scene s = two_rooms();
  solve_setup setup;
  const auto solver = solved(s, setup, true);
  const links_by_room before = count_links(*solver);
  const std::size_t elements_before = solved_mesh(*solver).element_count();
  set_solver_view(*solver, in_right_room(s));
  EXPECT_FALSE(solver->stats.remaining_final && refinement_done(*hierarchical_of(*solver)));
  solve(*solver, 1e-4);
  const links_by_room after = count_links(*solver);
  EXPECT_GE(after.left, before.left) << "the first view's links stay";
  EXPECT_GT(after.right, 2 * before.right) << "the new view's room is refined";
  EXPECT_GE(solved_mesh(*solver).element_count(), elements_before);
}

// With a view, the final gather is made at the vertices the view sees;
// the others keep the element solution, averaged to them by area.
TEST(ViewImportance, TheFinalGatherIsMadeWhereTheViewLooks) {
  const scene s = two_rooms();
  solve_setup plain_setup, led_setup;
  const auto plain = solved(s, plain_setup, false);
  const auto led = solved(s, led_setup, true);
  const hierarchical_solver& p = *hierarchical_of(*plain);
  const hierarchical_solver& h = *hierarchical_of(*led);
  ASSERT_TRUE(p.gathered_at.empty()) << "without a view, every vertex";
  ASSERT_FALSE(p.gathered.total.empty());
  const patch_mesh& mesh = h.mesh();
  ASSERT_EQ(h.gathered_at.size(), mesh.vertex_count());
  std::size_t seen = 0;
  const auto radiosity = make_snapshot(*led)->radiosity;
  const std::vector<rgb> averaged = element_to_vertex(mesh, h.light.total);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (mesh.positions[v].x > 0.0) {
      EXPECT_FALSE(h.gathered_at[v]) << "vertex " << v << " of the unseen room";
    }
    if (h.gathered_at[v]) {
      ++seen;
    } else if (!led->buried[v]) {  // the ceiling over the lamp's back takes its neighbours' values
      EXPECT_EQ(radiosity[v], averaged[v]) << "vertex " << v;
    }
  }
  EXPECT_GT(seen, mesh.vertex_count() / 4);
  EXPECT_LT(seen, 3 * mesh.vertex_count() / 4);
}

// The default minimum edge follows the scene's size; with a view, what the
// view sees may be split finer (the Cornell box's short block's shadow,
// seen close up), while a minimum edge given is kept.
TEST(ViewImportance, SeenElementsMaySplitBelowTheDefaultMinimumEdge) {
  const scene s = cornell();
  camera close_up = s.view;
  close_up.eye = vec3(400.0, 250.0, 50.0);
  close_up.target = vec3(380.0, 0.0, 200.0);
  close_up.fov_y_degrees = 30.0;
  // Elements under the default minimum edge, in the mesher's mesh (slivers
  // of the cuts) and in the solved one.
  std::size_t meshed[2] = {0, 0}, solved[2] = {0, 0};
  for (const bool given : {false, true}) {
    solver_settings settings;
    settings.view = close_up;
    if (given) settings.min_edge = 60.0;
    solve_setup setup;
    std::string error;
    ASSERT_TRUE(start_solve(s, settings, setup, error)) << error;
    solve(*setup.solver, 1e-3);
    const hierarchical_solver& h = *hierarchical_of(*setup.solver);
    const double default_minimum = h.meshes.input->max_edge / 8.0;
    for (std::size_t e = 0; e < h.meshes.input->element_count(); ++e)
      meshed[given] += element_longest_edge(*h.meshes.input, e) < 0.99 * default_minimum;
    for (std::size_t e = 0; e < h.mesh().element_count(); ++e)
      solved[given] += element_longest_edge(h.mesh(), e) < 0.99 * default_minimum;
  }
  EXPECT_GT(solved[0], meshed[0] + 100) << "seen elements split below the default minimum";
  EXPECT_EQ(solved[1], meshed[1]) << "a minimum edge given holds";
}

// The camera's rays run on TBB's threads or on one: the weights, and so
// the links, are the same.
TEST(ViewImportance, TheWeightsAreTheSameOnOneThreadOrMany) {
  const scene s = two_rooms();
  const patch_mesh mesh = mesh_of(s, 0.5);
  std::vector<double> weights[2];
  std::size_t links[2];
  for (const bool parallel : {false, true}) {
    radiosity_params params = hierarchical(2e-5);
    params.hierarchical.parallel = parallel;
    params.view = s.view;
    const auto solver = make_radiosity_solver(s, mesh, params);
    solve(*solver, 1e-3);
    weights[parallel] = hierarchical_of(*solver)->view.node;
    links[parallel] = hierarchical_of(*solver)->hierarchy.links.size();
  }
  ASSERT_FALSE(weights[0].empty());
  ASSERT_EQ(weights[0].size(), weights[1].size());
  EXPECT_EQ(links[0], links[1]);
  // The solution they are scaled by agrees to round-off (Hierarchical.ParallelAndSerialRunsAgree).
  for (std::size_t i = 0; i < weights[0].size(); ++i)
    EXPECT_NEAR(weights[0][i], weights[1][i], 1e-9 * std::max(1.0, weights[0][i])) << "node " << i;
}

// A view that sees no lit surface (it looks out of both rooms into
// nothing) leads nothing: every receiver weighs 1.
TEST(ViewImportance, AViewOfNothingLeavesTheSolveViewIndependent) {
  scene s = two_rooms();
  s.view.eye = vec3(0.0, 10.0, 0.0);
  s.view.target = vec3(0.0, 20.0, 0.0);
  s.view.up = vec3(0.0, 0.0, 1.0);
  solve_setup setup;
  const auto solver = solved(s, setup, true);
  EXPECT_TRUE(hierarchical_of(*solver)->view.node.empty());
  EXPECT_EQ(receiver_weight(*hierarchical_of(*solver), 0), 1.0);
}

}  // namespace
}  // namespace bounce
