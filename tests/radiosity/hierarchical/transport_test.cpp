// Transport over links: a cluster sends what its elements facing the
// receiver send.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "radiosity/hierarchical/fixtures.h"
#include "radiosity/hierarchical/solver.h"
#include "radiosity/solver.h"
#include "radiosity/transfer/form_factor.h"

namespace bounce {
namespace {

using std::numbers::pi;
using namespace test_support;  // the fixtures: hierarchical(), solve(), cornell(), ...

TEST(Hierarchical, AClusterSendsWhatItsElementsFacingTheReceiverSend) {
  // A closed cube (0.2 on a side, 1 above a floor, 0.8 under a ceiling)
  // whose top face alone emits, the rest black. Reached through the
  // cube's cluster, the ceiling must get what the top face sends it and
  // the floor nothing: a cluster's area-weighted mean radiosity would
  // send a sixth of the top face's light both ways.
  scene s;
  const int black = add_material(s, rgb(0.0));
  const int light = add_material(s, rgb(0.0), rgb(10.0));
  const int white = add_material(s, rgb(0.5));
  test_support::add_closed_box(s, vec3(-0.1, 1.0, -0.1), vec3(0.1, 1.2, 0.1), black);
  for (surface& face : s.surfaces) {  // facing out: a solid
    std::vector<int>& corners = std::get<polygon_mesh>(face.geometry).faces[0].position;
    std::reverse(corners.begin(), corners.end());
  }
  std::get<polygon_mesh>(s.surfaces[5].geometry).faces[0].material = light;  // y = 1.2, facing up
  const std::vector<vec3> top = {{-0.1, 1.2, -0.1}, {-0.1, 1.2, 0.1}, {0.1, 1.2, 0.1}, {0.1, 1.2, -0.1}};
  add_polygon(s, {{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}}, white);  // floor, facing up
  add_polygon(s, {{-2, 2, -2}, {2, 2, -2}, {2, 2, 2}, {-2, 2, 2}}, white);  // ceiling, facing down
  const patch_mesh mesh = mesh_of(s, 1.0);
  auto solver = make_radiosity_solver(s, mesh, hierarchical(1e-3));
  solve(*solver, 1e-9);
  const hierarchical_solver& h = *hierarchical_of(*solver);
  // Links whose source is a cluster of the cube's faces alone (its box within the cube's).
  std::size_t cluster_links = 0;
  for (const hierarchy_link& link : h.hierarchy.links.links) {
    const cluster_node& source = h.hierarchy.tree.nodes[std::size_t(link.source)];
    cluster_links += !source.oriented && source.lo.y >= 0.99 && source.hi.y <= 1.21;
  }
  EXPECT_GT(cluster_links, 100u);  // 162 of 1038
  // Power the ceiling and the floor gather straight from the emitter, against Lambert's formula
  // for the top face integrated over the ceiling (midpoint rule, 200 x 200).
  double ceiling = 0.0, floor = 0.0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const double y = h.hierarchy.tree.nodes[std::size_t(h.hierarchy.tree.leaf_of_element[e])].centroid.y;
    const double power = h.gathered.direct[e].g / 0.5 * mesh.element_areas[e];  // rho x irradiance from emitters
    if (y > 1.9) ceiling += power;
    if (y < 0.1) floor += power;
  }
  double exact = 0.0;
  const int n = 200;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const vec3 p(-2 + 4.0 * (i + 0.5) / n, 2.0, -2 + 4.0 * (j + 0.5) / n);
      exact += point_polygon_form_factor(p, vec3(0, -1, 0), top) * 16.0 / (n * n);
    }
  exact *= pi * 10.0;
  std::printf("cube's top face: ceiling %.4f W (exact %.4f), floor %.4f W\n", ceiling, exact, floor);
  EXPECT_NEAR(ceiling / exact, 1.0, 0.05);  // measured 0.970
  EXPECT_LT(floor, 1e-6 * exact);           // measured 0
}

}  // namespace
}  // namespace bounce
