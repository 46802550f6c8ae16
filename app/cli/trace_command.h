// `bounce trace`: solve (the radiosity pass), then ray trace a still of the
// camera (Whitted; two-pass with a final gather and caustics, plain or
// progressive) or path trace a reference; PNG and PFM out.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "cli/camera_options.h"
#include "radiosity/solver_settings.h"

namespace CLI {
class App;
}  // namespace CLI

namespace bounce {

struct trace_options {
  std::string scene;                          // SCENE; empty: the embedded Cornell box
  solver_settings solver;                     // the solver options: the radiosity pass
  bool view_independent = false;              // --view-independent: the camera does not lead the radiosity pass
  camera_options camera;                      // the camera overrides
  std::string out_path = "bounce-trace.png";  // --out
  std::string pfm_path;                       // --pfm: linear radiance
  std::string integrator = "whitted";         // whitted | twopass | ppm | path
  int spp = 0;                                // 0: default_spp(integrator)
  int adaptive_spp = 0;
  int depth = 0;  // 0: the integrator's default
  int light_samples = 16;
  std::string direct = "rays";    // rays | radiosity: where the Whitted tracer's direct light comes from
  bool no_radiosity = false;      // one-pass Whitted with a constant ambient term
  std::optional<double> ambient;  // its irradiance; default: the mean indirect irradiance of a coarse solution
  std::uint64_t seed = 1;
  double exposure = 1.0;
  long photons = -1;             // twopass, ppm (per pass): -1 = default_caustic_photons
  int passes = 32;               // ppm
  int gather_rays = 256;         // twopass, ppm
  double cache_accuracy = 0.25;  // twopass, ppm: Ward's a; 0 = no cache
  bool ray_baseline = false;     // also time bare closest-hit queries of the pixel-centre rays
  std::string stats_path;        // --stats: trace (and radiosity pass) statistics as JSON
};

void add_trace_options(CLI::App& command, trace_options& options);

// Samples per pixel when --spp is not given: enough for a clean picture of
// the Cornell box (see --help).
inline int default_spp(const std::string& integrator) {
  if (integrator == "path") return 256;
  return integrator == "whitted" ? 16 : 4;
}

// Options the chosen solver, integrator and passes would ignore (e.g.
// --ambient without --no-radiosity, solver options with the path tracer,
// --exposure with a linear --out), and output paths that cannot be
// written; an error message naming them, or an empty string. May settle
// the solver the options choose (check_solver_options).
std::string check_trace_options(const CLI::App& command, trace_options& options);

// Loads the options' scene with their camera, solves it (the radiosity
// pass) and traces the still.
int run_trace(const trace_options& options);

}  // namespace bounce
