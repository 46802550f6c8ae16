// Radiance is never negative, whenever the solver stops: a still traced
// from the hierarchical solution after every one of its first steps, on
// the reproducer of a negative picture (a floor, a wall and a lamp that is
// a non-planar quad; `trace --until 0.05` gave a mean of -0.0021).
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "radiosity/solve.h"
#include "scene/scene_io.h"
#include "test_files.h"
#include "trace/radiosity_field.h"
#include "trace/ray_scene.h"
#include "trace/ray_tracer.h"

namespace bounce {
namespace {

using test_support::scratch_dir;

TEST(EarlyStop, TheHierarchicalSolutionAndItsStillsAreNeverNegative) {
  scratch_dir dir;
  dir.write("probe.mtl", "newmtl white\nKd 0.7 0.7 0.7\nnewmtl lamp\nKd 0.5 0.5 0.5\nKe 5 5 5\n"
                         "newmtl tex\nKd 0.6 0.6 0.6\nKs 0.2 0.2 0.2\nNs 20\nillum 2\n");
  const std::string path = dir.write("probe.obj",
                                     "mtllib probe.mtl\n"
                                     "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 2 -1\nv 1 2 -1\nv 1 2 -1\n"
                                     "v -0.3 1.9 -0.3\nv 0.3 1.9 -0.3\nv 0.3 1.9 0.3\nv -0.3 1.9 0.3\n"
                                     "usemtl white\nf 4 3 2 1\nf 1 2 6 5\nusemtl lamp\nf 7 8 9 10\n"
                                     "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\nv -0.5 0.5 0\nv 0.5 0.5 0\nv 0 1.0 0\n"
                                     "usemtl tex\nf 11/1/1 12/2/1 13/3/1\n"
                                     "o second\nv 0.2 0.1 0.2\nv 0.6 0.1 0.2\nv 0.4 0.1 0.6\nusemtl white\nf -1 -2 -3\n");
  scene s;
  load_report report;
  ASSERT_TRUE(load_scene(path, s, report)) << report.error;
  s.view.width = s.view.height = 32;
  solve_setup setup;
  std::string error;
  ASSERT_TRUE(start_solve(s, solver_settings{}, setup, error)) << error;
  const ray_scene rays(s);
  int steps = 0;
  double least_pixel = 0.0, least_indirect = 0.0;
  for (; steps < 8 && step_solver(*setup.solver); ++steps) {
    const auto solution = make_snapshot(*setup.solver);

    const patch_mesh& mesh = solved_mesh(*setup.solver);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
      for (int c = 0; c < 3; ++c) {
        const double indirect = solution->radiosity[v][c] - mesh.vertex_emission[v][c] - solution->direct[v][c];
        least_indirect = std::min(least_indirect, indirect);
      }
    const radiosity_field field(mesh, solution->radiosity, solution->direct, solution->ambient, solution->caustic);
    trace_params p;
    p.spp = 4;
    const image still = trace_image(s, s.view, rays, &field, p);
    for (float x : still.pixels) least_pixel = std::min(least_pixel, double(x));
  }
  EXPECT_GE(steps, 4);
  // Two causes, both measured here before the fix: refined links brought
  // more direct light than the iterate held (B - E - direct down to -0.32,
  // fixed by raising the iterate to E + direct: closer to the solution), and
  // the ambient term took light away where the signed residual was
  // negative (pixels down to -0.012 even so; it now adds only light still
  // to come). Round-off only is left.
  EXPECT_GE(least_indirect, -1e-12);
  EXPECT_GE(least_pixel, 0.0);
  // And the ambient term itself.
  EXPECT_GE(std::min({make_snapshot(*setup.solver)->ambient.r, make_snapshot(*setup.solver)->ambient.g,
                      make_snapshot(*setup.solver)->ambient.b}),
            0.0);
}

}  // namespace
}  // namespace bounce
