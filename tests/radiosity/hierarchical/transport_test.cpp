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
  // What the ceiling's and the floor's vertices gather straight from the
  // emitter, against Lambert's formula for the top face at each.
  const patch_mesh& solved = h.mesh();
  double worst = 0.0, brightest = 0.0, ceiling = 0.0, exact = 0.0, floor = 0.0;
  for (std::size_t v = 0; v < solved.vertex_count(); ++v) {
    const vec3& p = solved.receive_points[v];
    const double got = h.gathered.direct[v].g;  // rho x irradiance from emitters
    if (p.y < 0.1) floor = std::max(floor, got);
    if (p.y < 1.9) continue;
    const double expected = 0.5 * pi * 10.0 * point_polygon_form_factor(p, solved.normals[v], top);
    worst = std::max(worst, std::abs(got - expected));
    brightest = std::max(brightest, expected);
    ceiling += got;
    exact += expected;
  }
  std::printf("cube's top face: ceiling %.4f of exact, worst vertex off by %.4f of the brightest, floor %g\n",
              ceiling / exact, worst / brightest, floor);
  EXPECT_NEAR(ceiling / exact, 1.0, 0.02);  // measured 1.0099
  // The far corners, where the cube is 1/150 of its brightest, are the
  // worst: links from the cube's cluster to coarse parts of the ceiling.
  EXPECT_LT(worst / brightest, 0.02);  // measured 0.0115
  EXPECT_LT(floor, 1e-6 * exact);      // measured 0
}

}  // namespace
}  // namespace bounce
