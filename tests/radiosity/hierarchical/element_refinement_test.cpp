// Elements split below the input mesh where links need them.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "radiosity/hierarchical/fixtures.h"
#include "radiosity/hierarchical/solver.h"
#include "radiosity/solver.h"

namespace bounce {
namespace {

using std::numbers::pi;
using namespace test_support;  // the fixtures: hierarchical(), solve(), cornell(), ...

TEST(Hierarchical, ElementsAreSplitOnlyWhereLinksNeedThem) {
  const scene s = cornell();
  const patch_mesh mesh = mesh_of(s, 100.0);
  auto solver = make_radiosity_solver(s, mesh, splitting(1e-5, 5.0));
  solve(*solver, 1e-3);
  const hierarchical_solver& h = *hierarchical_of(*solver);
  ASSERT_TRUE(refined_mesh(*solver));
  ASSERT_EQ(&solved_mesh(*solver), &h.mesh());
  const patch_mesh& refined = solved_mesh(*solver);
  EXPECT_GT(h.progress.element_passes, 0);
  EXPECT_GT(refined.element_count(), 2 * mesh.element_count());
  // The published solution and the view's mesh are the refined ones.
  EXPECT_EQ(make_snapshot(*solver)->radiosity.size(), refined.vertex_count());
  EXPECT_EQ(h.residual.size(), refined.element_count());
  // Pieces tile their elements: the area is unchanged, and no split went
  // below the minimum edge (a bisected edge was longer than it).
  EXPECT_NEAR(total_area(refined), total_area(mesh), 1e-9 * total_area(mesh));
  for (std::size_t e = 0; e < refined.element_count(); ++e) ASSERT_GT(element_longest_edge(refined, e), 2.5 - 1e-9);

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
  auto solver = make_radiosity_solver(s, mesh, splitting(1e-6, 0.05));
  solve(*solver, 1e-9, 300);
  ASSERT_TRUE(refined_mesh(*solver));  // the corners of the box need finer elements
  const std::size_t refined = solved_mesh(*solver).element_count();
  EXPECT_GT(refined, mesh.element_count());
  const double exact = pi / (1.0 - 0.99);
  const auto solution = make_snapshot(*solver);
  for (const rgb& b : solution->radiosity) ASSERT_NEAR(b.g, exact, 1e-7 * exact);
  // A restart goes back to the mesher's mesh, and solving again refines it the same way.
  restart_solver(*solver);
  EXPECT_EQ(&solved_mesh(*solver), &mesh);
  EXPECT_EQ(make_snapshot(*solver)->radiosity.size(), mesh.vertex_count());
  solve(*solver, 1e-9, 300);
  EXPECT_EQ(solved_mesh(*solver).element_count(), refined);
}

}  // namespace
}  // namespace bounce
