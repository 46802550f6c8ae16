// The memory a solve needs, estimated before meshing (memory_estimate.h):
// the element count it rests on is at most what the mesher makes, so a
// refusal never turns away a scene that would have fitted; and the solve
// refuses, naming both figures, what does not fit.
#include <cstdio>

#include <gtest/gtest.h>

#include "child_process.h"
#include "mesh_builders.h"
#include "radiosity/memory_estimate.h"
#include "radiosity/solve.h"

namespace bounce {
namespace {

// A scene, the mesher's element count for it, and the estimate's.
void expect_estimate_at_most_the_mesh(const scene& s, double low_share) {
  const solver_settings settings;
  const solve_memory need = estimate_solve_memory(s, settings);
  solve_setup setup;
  std::string error;
  ASSERT_TRUE(mesh_for_solve(s, settings, setup, error)) << error;
  const double elements = double(setup.mesh->element_count());
  EXPECT_LE(need.elements, 1.05 * elements) << s.source;
  EXPECT_GE(need.elements, low_share * elements) << s.source;
  EXPECT_DOUBLE_EQ(need.bytes, solve_base_bytes + need.elements * solve_bytes_per_element);
}

TEST(MemoryEstimate, CountsNoMoreElementsThanTheMesherMakes) {
  // The Cornell box: the contact cuts add elements the estimate does not
  // foresee (832 of 1,372).
  expect_estimate_at_most_the_mesh(test_support::default_cornell_box(), 0.5);
  // Triangles far smaller than an element: one element each, at least.
  scene fine;
  test_support::add_material(fine, rgb(0.5));
  for (int i = 0; i < 400; ++i) {
    const double x = (i % 20) * 0.05, z = (i / 20) * 0.05;
    test_support::add_polygon(fine, {{x, 0, z}, {x, 0, z + 0.04}, {x + 0.04, 0, z}}, 0);
  }
  test_support::add_polygon(fine, {{0, 3, 0}, {1, 3, 0}, {1, 3, 1}, {0, 3, 1}}, 0);
  expect_estimate_at_most_the_mesh(fine, 0.9);
}

// Under a 1 GB address-space limit (in a child), a mesh of a million
// elements is refused before it is built, with the figures.
TEST(MemoryEstimate, ASolveThatCannotFitIsRefusedBeforeMeshing) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer maps more address space than any such limit";
#endif
  scene s;
  test_support::add_material(s, rgb(0.5), rgb(1.0));
  test_support::add_polygon(s, {{0, 0, 0}, {0, 0, 100}, {100, 0, 100}, {100, 0, 0}}, 0);
  solver_settings settings;
  settings.max_edge = 0.2;  // about a million elements over 100 x 100
  EXPECT_TRUE(test_support::holds_under_limit(RLIMIT_AS, 1'000'000'000, [&] {
    solve_setup setup;
    std::string error;
    const bool refused = !mesh_for_solve(s, settings, setup, error) &&
                         error.find(
                             "solving needs at least 2.06 GB (about 1 million elements at max edge 0.2, 2 kB "
                             "each), more than the ") == 0 &&
                         error.find("use a larger --max-edge") != std::string::npos;
    if (!refused) std::fprintf(stderr, "%s\n", error.c_str());
    return refused;
  }));
}

}  // namespace
}  // namespace bounce
