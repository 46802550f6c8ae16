// `bounce solve`: mesh, run the solver to the criterion, report.
#pragma once

#include <string>

#include "radiosity/bake.h"
#include "radiosity/solver_settings.h"

namespace CLI {
class App;
}  // namespace CLI

namespace bounce {

struct solve_options {
  std::string scene;          // SCENE; empty: the embedded Cornell box
  solver_settings solver;     // the solver options
  std::string ply_path;       // --ply: a bake to PLY at the automatic exposure
  std::string bake_path;      // bake --out
  bake_settings bake;         // bake --exposure, --parts
  std::string stats_path;     // --stats: solver statistics as JSON
  bool reference = false;     // --reference: also solve the full matrix and compare
  bool ray_baseline = false;  // --ray-baseline: replay recorded solver rays through rtcOccluded1
};

void add_solve_options(CLI::App& command, solve_options& options);

// Solver options the chosen solver ignores (--reference and --ray-baseline
// measure the progressive solver, and choose it), and output paths that
// cannot be written; an error message or an empty string.
std::string check_solve_options(const CLI::App& command, solve_options& options);

// Loads the options' scene (its own camera: solve renders nothing) and
// solves it.
int run_solve(const solve_options& options);

}  // namespace bounce
