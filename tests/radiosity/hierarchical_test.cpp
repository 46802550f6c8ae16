// Hierarchical radiosity with clustering against exact answers, the
// element-level solution it converges to, and its own invariants.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh_builders.h"
#include "radiosity/hierarchical/cluster_tree.h"
#include "radiosity/transfer/form_factor.h"
#include "radiosity/hierarchical/diagnostics.h"
#include "radiosity/hierarchical/solver.h"
#include "radiosity/radiosity.h"
#include "scene/scene_io.h"

namespace bounce {
namespace {

using std::numbers::pi;
using test_support::add_material;
using test_support::add_polygon;
using test_support::furnace;

using test_support::mesh_of;

radiosity_params hierarchical(double tolerance) {
  radiosity_params p;
  p.method = solver_method::hierarchical;
  p.hierarchical.tolerance = tolerance;
  return p;
}

// Steps until the links are final and the residual is below `fraction`.
void solve(radiosity_state& state, double fraction, int max_steps = 400) {
  for (int i = 0; i < max_steps; ++i) {
    if (state.stats.links_final && state.lights_shot && state.stats.unshot_fraction <= fraction) return;
    if (!step_radiosity(state)) return;
  }
  ADD_FAILURE() << "not converged in " << max_steps << " steps: residual " << state.stats.unshot_fraction;
}

scene cornell() {
  return test_support::default_cornell_box();
}

double largest_relative_difference(const std::vector<rgb>& a, const std::vector<rgb>& b) {
  double largest = 0.0, scale = 0.0;
  for (const rgb& x : b) scale = std::max({scale, x.r, x.g, x.b});
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) largest = std::max(largest, std::abs(a[i][c] - b[i][c]) / scale);
  return largest;
}

TEST(Hierarchical, FurnaceIsExactAtHighReflectance) {
  for (double rho : {0.5, 0.99, 0.999}) {
    const scene s = furnace(rho);
    const patch_mesh mesh = mesh_of(s, 0.25);
    auto state = make_radiosity_state(s, mesh, hierarchical(1e-4));
    solve(*state, 1e-9, 200);
    ASSERT_TRUE(state->hierarchy->progress.closed);
    const double exact = pi / (1.0 - rho);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
      ASSERT_NEAR(state->radiosity[v].g, exact, 1e-7 * exact) << "rho " << rho << " vertex " << v;
    // Krylov iterations: a few dozen operator applications even at 0.999
    // (Jacobi would need thousands).
    EXPECT_LT(state->hierarchy->progress.operator_applications, 150u) << "rho " << rho;
  }
}

TEST(Hierarchical, ConvergesToTheElementLevelSolutionAsTheToleranceFalls) {
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 150.0);
  ASSERT_LT(mesh.element_count(), 1500u);
  double previous = INFINITY;
  for (double tolerance : {1e-3, 1e-5, 1e-12}) {
    auto state = make_radiosity_state(s, mesh, hierarchical(tolerance));
    solve(*state, 1e-12);
    const hierarchical_solver& h = *state->hierarchy;
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
  auto state = make_radiosity_state(s, mesh, hierarchical(1e-3));
  solve(*state, 1e-9);
  const hierarchical_solver& h = *state->hierarchy;
  double reflected = 0.0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) reflected += h.gathered.total[e].g * mesh.element_areas[e];
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

// Whether a floor point lies outside the short block's footprint (the
// official data's corners) but within 30 mm of it: its contact shadow.
bool near_short_block(const vec3& p) {
  const vec2 corners[4] = {{130, 65}, {82, 225}, {240, 272}, {290, 114}};
  const vec2 q(p.x, p.z);
  double nearest = INFINITY;
  int inside = 0;
  for (int k = 0; k < 4; ++k) {
    const vec2 a = corners[k], b = corners[(k + 1) % 4];
    const double t = std::clamp(glm::dot(q - a, b - a) / glm::dot(b - a, b - a), 0.0, 1.0);
    nearest = std::min(nearest, glm::length(q - (a + t * (b - a))));
    const vec2 edge = b - a, to = q - a;
    inside += edge.x * to.y - edge.y * to.x > 0.0 ? 1 : -1;
  }
  return std::abs(inside) != 4 && nearest < 30.0;
}

TEST(Hierarchical, LinksConcentrateAtContactsAndShadows) {
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 15.0);
  auto state = make_radiosity_state(s, mesh, hierarchical(1e-5));
  solve(*state, 1e-3);
  const std::vector<double> density = link_density(*state->hierarchy);
  // Floor elements within 30 mm of the short block's foot against open floor.
  double near_sum = 0.0, open_sum = 0.0;
  int near_count = 0, open_count = 0;
  const hierarchical_solver& h = *state->hierarchy;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const vec3 c = h.hierarchy.tree.nodes[h.hierarchy.tree.leaf_of_element[e]].centroid;
    const vec3 n = mesh.element_normals[e];
    if (n.y > 0.99 && c.y < 1.0 && near_short_block(c)) {
      near_sum += density[e];
      ++near_count;
    }
    // Open floor in front of the right wall, 70 mm or more from either block.
    if (n.y > 0.99 && c.y < 1.0 && c.x > 360.0 && c.x < 540.0 && c.z > 10.0 && c.z < 175.0) {
      open_sum += density[e];
      ++open_count;
    }
  }
  ASSERT_GT(near_count, 0);
  ASSERT_GT(open_count, 0);
  std::printf("links per unit area: contact %g, open floor %g\n", near_sum / near_count, open_sum / open_count);
  EXPECT_GT(near_sum / near_count, 2.0 * open_sum / open_count);
}

double longest_edge(const patch_mesh& mesh, std::size_t e) {
  double longest = 0.0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(
        longest, glm::length(mesh.positions[mesh.elements[e][(k + 1) % 3]] - mesh.positions[mesh.elements[e][k]]));
  return longest;
}

radiosity_params splitting(double tolerance, double min_edge) {
  radiosity_params p = hierarchical(tolerance);
  p.hierarchical.split_elements = true;
  p.hierarchical.min_edge = min_edge;
  return p;
}

TEST(Hierarchical, ElementsAreSplitOnlyWhereLinksNeedThem) {
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 100.0);
  auto state = make_radiosity_state(s, mesh, splitting(1e-5, 5.0));
  solve(*state, 1e-3);
  const hierarchical_solver& h = *state->hierarchy;
  ASSERT_TRUE(state->refined_mesh);
  ASSERT_EQ(state->mesh, &h.mesh());
  const patch_mesh& refined = *state->mesh;
  EXPECT_GT(h.progress.element_passes, 0);
  EXPECT_GT(refined.element_count(), 2 * mesh.element_count());
  // The published solution and the view's mesh are the refined ones.
  EXPECT_EQ(state->radiosity.size(), refined.vertex_count());
  EXPECT_EQ(state->unshot.size(), refined.element_count());
  // Pieces tile their elements: the area is unchanged, and no split went
  // below the minimum edge (a bisected edge was longer than it).
  EXPECT_NEAR(total_area(refined), total_area(mesh), 1e-9 * total_area(mesh));
  for (std::size_t e = 0; e < refined.element_count(); ++e) ASSERT_GT(longest_edge(refined, e), 2.5 - 1e-9);

  // Fine at the short block's contact shadow, coarse on open floor.
  double near_area = 0.0, open_area = 0.0;
  int near_count = 0, open_count = 0;
  for (std::size_t e = 0; e < refined.element_count(); ++e) {
    const vec3 c = h.hierarchy.tree.nodes[h.hierarchy.tree.leaf_of_element[e]].centroid;
    if (refined.element_normals[e].y < 0.99 || c.y > 1.0) continue;
    if (near_short_block(c)) {
      near_area += refined.element_areas[e];
      ++near_count;
    }
    if (c.x > 360.0 && c.x < 540.0 && c.z > 10.0 && c.z < 175.0) {
      open_area += refined.element_areas[e];
      ++open_count;
    }
  }
  ASSERT_GT(near_count, 0);
  ASSERT_GT(open_count, 0);
  std::printf("%zu -> %zu elements in %d passes; mean area: contact %g, open floor %g\n", mesh.element_count(),
              refined.element_count(), h.progress.element_passes, near_area / near_count, open_area / open_count);
  EXPECT_LT(near_area / near_count, 0.4 * open_area / open_count);
  // The middle of the back wall, lit smoothly, stays coarser too.
  double wall_area = 0.0;
  int wall_count = 0;
  for (std::size_t e = 0; e < refined.element_count(); ++e) {
    const vec3 c = h.hierarchy.tree.nodes[h.hierarchy.tree.leaf_of_element[e]].centroid;
    if (refined.element_normals[e].z < -0.99 && c.z > 550.0 && std::abs(c.x - 278.0) < 120.0 &&
        std::abs(c.y - 274.0) < 120.0) {
      wall_area += refined.element_areas[e];
      ++wall_count;
    }
  }
  ASSERT_GT(wall_count, 0);
  std::printf("mean area: middle of the back wall %g\n", wall_area / wall_count);
  EXPECT_GT(wall_area / wall_count, 2.0 * near_area / near_count);
}

TEST(Hierarchical, SplittingKeepsTheFurnaceExactAndRestartsOnTheInputMesh) {
  const scene s = furnace(0.99);
  const patch_mesh mesh = mesh_of(s, 0.5);
  auto state = make_radiosity_state(s, mesh, splitting(1e-6, 0.05));
  solve(*state, 1e-9, 300);
  ASSERT_TRUE(state->refined_mesh);  // the corners of the box need finer elements
  const std::size_t refined = state->mesh->element_count();
  EXPECT_GT(refined, mesh.element_count());
  const double exact = pi / (1.0 - 0.99);
  for (const rgb& b : state->radiosity) ASSERT_NEAR(b.g, exact, 1e-7 * exact);
  // A restart goes back to the mesher's mesh, and solving again refines it the same way.
  restart_radiosity(*state);
  EXPECT_EQ(state->mesh, &mesh);
  EXPECT_EQ(state->radiosity.size(), mesh.vertex_count());
  solve(*state, 1e-9, 300);
  EXPECT_EQ(state->mesh->element_count(), refined);
}

TEST(Hierarchical, PointLightGivesTheInverseSquareLawAtElementCentres) {
  scene s;
  const int white = add_material(s, rgb(0.5));
  add_polygon(s, {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}, white);
  s.lights.push_back({vec3(0.3, 2, 0.1), rgb(10, 20, 30)});
  const patch_mesh mesh = mesh_of(s, 0.5);
  auto state = make_radiosity_state(s, mesh, hierarchical(1e-5));
  solve(*state, 1e-12);
  const hierarchical_solver& h = *state->hierarchy;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const vec3 d = s.lights[0].position - h.hierarchy.tree.nodes[h.hierarchy.tree.leaf_of_element[e]].centroid;
    EXPECT_NEAR(h.light.total[e].b, 0.5 * 30 * d.y / std::pow(glm::length(d), 3.0), 1e-12);
    EXPECT_EQ(h.light.direct[e], h.light.total[e]);
  }
}

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
  auto state = make_radiosity_state(s, mesh, hierarchical(1e-3));
  solve(*state, 1e-9);
  const hierarchical_solver& h = *state->hierarchy;
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

TEST(Hierarchical, LinksFromInnerNodesCarryTheirSourcesFormFactor) {
  // The Cornell box at the default tolerance: a link from an inner node to
  // an oriented receiver carries the form factor from the receiver's
  // centre to the source, here summed exactly over all the source's
  // elements (Lambert's formula for each that faces the receiver). The
  // disc estimate (a disc of the source's projected area at its centroid)
  // errs by the second order of the source's angular size, and the same
  // way in a box: its sums over links come out 1-2% short, and that much
  // light goes missing at every bounce.
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 96.0);
  auto state = make_radiosity_state(s, mesh, hierarchical(1e-5));
  solve(*state, 0.01);
  const hierarchical_solver& h = *state->hierarchy;
  const patch_mesh& m = h.mesh();
  auto elements_under = [&](int node, auto&& self, std::vector<int>& out) -> void {
    const cluster_node& c = h.hierarchy.tree.nodes[std::size_t(node)];
    if (c.leaf()) return out.push_back(c.element);
    for (int k = c.first_child; k < c.first_child + c.child_count; ++k) self(k, self, out);
  };
  double carried = 0.0, disc = 0.0, exact = 0.0;
  std::size_t examined = 0;
  for (std::size_t l = 0; l < h.hierarchy.links.size(); l += 7) {
    const hierarchy_link& link = h.hierarchy.links.links[l];
    const cluster_node& r = h.hierarchy.tree.nodes[std::size_t(link.receiver)];
    const cluster_node& source = h.hierarchy.tree.nodes[std::size_t(link.source)];
    if (source.leaf() || !r.oriented) continue;
    std::vector<int> elements;
    elements_under(link.source, elements_under, elements);
    double f = 0.0;
    for (const int e : elements) {
      const glm::ivec3 t = m.elements[std::size_t(e)];
      const vec3 polygon[3] = {m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]};
      if (glm::dot(m.element_normals[std::size_t(e)], r.centroid - polygon[0]) > 0.0)
        f += point_polygon_form_factor(r.centroid, r.normal, polygon);
    }
    const vec3 d = source.centroid - r.centroid;
    const double r2 = glm::dot(d, d);
    const double send = projected_area(source, -d / std::sqrt(r2));
    disc += std::max(0.0, glm::dot(r.normal, d) / std::sqrt(r2)) * send / (pi * r2 + send);
    carried += double(link.factor);
    exact += f;
    ++examined;
  }
  ASSERT_GT(examined, 1000u);
  std::printf("%zu links from inner nodes: carried / exact %.4f, disc estimate / exact %.4f\n", examined,
              carried / exact, disc / exact);
  EXPECT_NEAR(carried / exact, 1.0, 0.003);  // measured 0.9999; the disc estimate alone 0.990
}

TEST(Hierarchical, RefinesBetweenIterationsAndPublishesEveryStep) {
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 40.0);
  auto state = make_radiosity_state(s, mesh, hierarchical(1e-5));
  std::size_t links = 0;
  double tolerance = INFINITY;
  int refinements = 0;
  for (int step = 0; step < 200 && step_radiosity(*state); ++step) {
    // Every step publishes vertex radiosity for the view.
    ASSERT_EQ(state->radiosity.size(), mesh.vertex_count());
    const hierarchical_solver& h = *state->hierarchy;
    if (h.progress.tolerance < tolerance) {
      EXPECT_GE(h.hierarchy.links.size(), links);  // links are only ever split
      links = h.hierarchy.links.size();
      tolerance = h.progress.tolerance;
      ++refinements;
    }
    if (state->stats.links_final && state->stats.unshot_fraction < 1e-6) break;
  }
  EXPECT_EQ(refinements, 4);  // the first links and three refinements
  EXPECT_DOUBLE_EQ(tolerance, 1e-5);
  EXPECT_LT(state->stats.unshot_fraction, 1e-6);
}

TEST(Hierarchical, LinkCostAndLimit) {
  EXPECT_EQ(sizeof(hierarchy_link), 16u);
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 40.0);
  radiosity_params p = hierarchical(1e-6);
  p.hierarchical.max_links = 5000;
  auto state = make_radiosity_state(s, mesh, p);
  solve(*state, 1e-3);
  const hierarchical_solver& h = *state->hierarchy;
  // Past the limit no link is split: the pairs under way when it was hit
  // become links, at most two per node of the tree.
  EXPECT_LE(h.hierarchy.links.size(), 5000u + 2u * h.hierarchy.tree.nodes.size());
  EXPECT_NE(h.progress.warning.find("link limit"), std::string::npos);
  for (const rgb& b : state->radiosity) ASSERT_TRUE(std::isfinite(b.r) && b.r >= 0.0);
}

TEST(Hierarchical, ParallelAndSerialRunsAgree) {
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 60.0);
  radiosity_params serial = hierarchical(1e-5);
  serial.hierarchical.parallel = false;
  auto a = make_radiosity_state(s, mesh, serial);
  auto b = make_radiosity_state(s, mesh, hierarchical(1e-5));
  solve(*a, 1e-6);
  solve(*b, 1e-6);
  ASSERT_EQ(a->hierarchy->hierarchy.links.size(), b->hierarchy->hierarchy.links.size());
  EXPECT_LT(largest_relative_difference(a->radiosity, b->radiosity), 1e-12);
}

}  // namespace
}  // namespace bounce
