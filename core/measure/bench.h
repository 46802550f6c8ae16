// Speed against error: runs one solver setting on one scene and records its
// error at many points along the way (one run, not one run per stop), for
// `bounce bench`. GL-free; the error of a solution is measured against a
// closed form per vertex where one exists (exact_solutions.h), otherwise
// through a picture of the solution against a path-traced reference
// picture (picture_judge.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "measure/curves.h"
#include "measure/exact_solutions.h"
#include "measure/picture_judge.h"
#include "radiosity/solver_settings.h"

namespace bounce {

enum class bench_solver {
  radiosity,    // the solver solver.method names (hierarchical or progressive), error recorded at stops along the run
  reference,    // full matrix: LU and Gauss-Seidel, one point each
  path_tracer,  // the reference integrator itself, at doubling sample counts
};

struct bench_setting {
  bench_solver kind = bench_solver::radiosity;
  // Solver (method), mesh, form factors, adaptive meshing, link tolerance
  // and the stop (radiosity; the path tracer stops at stop.seconds too).
  solver_settings solver = [] {
    solver_settings d;
    d.stop.remaining = 1e-3;
    d.stop.seconds = 10.0;
    return d;
  }();
  bool measure_error = true;  // false: timings only (the growth runs)
  int path_max_spp = 1 << 14;
};

struct bench_result {
  std::size_t elements = 0, vertices = 0, patches = 0;
  double setup_seconds = 0.0;                   // meshing, BVH and form-factor set-up
  double first_picture_seconds = not_measured;  // until every emitter has shot: direct light everywhere
  double seconds_per_step = not_measured;       // solver time per step (progressive: per shot)
  std::uint64_t links = 0;                      // hierarchical: links at the end of the run
  double link_tolerance = not_measured;         // hierarchical: the oracle's tolerance at the end
  bool links_final = true;                      // hierarchical: the tolerance reached its final value
  std::vector<bench_curve> curves;
  std::string error;  // why the run could not be made (e.g. too large for the full matrix)
};

// Runs `setting` on `s` (whose view is the bench picture's camera and size).
bench_result run_bench(const scene& s, const bench_setting& setting, const bench_truth& truth);

}  // namespace bounce
