// `bounce solve`: mesh, run the progressive solver to the criterion, report.
#pragma once

#include <string>

#include "cli/cli.h"

namespace bounce {

struct solve_options {
  std::string ply_path;       // --ply
  std::string stats_path;     // --stats: solver statistics as JSON
  bool reference = false;     // --reference: also solve the full matrix and compare
  bool ray_baseline = false;  // --ray-baseline: replay recorded solver rays through rtcOccluded1
};

int run_solve(const scene& s, const solver_settings& solver, const solve_options& extra);

}  // namespace bounce
