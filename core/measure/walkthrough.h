// A walkthrough: the radiosity solution is made once, without a view, and
// every view along a path is drawn from it; the path tracer renders every
// view anew, at doubling sample counts until it is as accurate as the
// radiosity picture of that view. Both are judged per view against a
// path-traced reference (picture_judge.h). This is where a view-independent
// solution earns its keep: its cost is paid once. GL-free.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"
#include "radiosity/solver_settings.h"
#include "scene/scene.h"

namespace bounce {

struct walkthrough_settings {
  solver_settings solver;  // its stop bounds the one solve (settings.view is ignored: no view leads it)
  int still_spp = 4;       // the radiosity picture: the Gouraud view's diffuse term, ray cast
  int path_max_spp = 64;   // the path tracer gives up on a view after this many samples per pixel
  int downsample = 4;      // the judge's box filter
};

struct walkthrough_view {
  double radiosity_error = 0.0;    // relative RMSE of the view drawn from the solution
  double radiosity_seconds = 0.0;  // drawing it (ray cast at still_spp)
  double path_error = 0.0;         // the path tracer's, at path_spp
  int path_spp = 0;                // the fewest doubling samples that reached radiosity_error, or path_max_spp
  double path_seconds = 0.0;       // tracing that picture
  bool path_reached = false;       // path_error <= radiosity_error
};

struct walkthrough_result {
  double setup_seconds = 0.0;  // meshing and the solver's set-up
  double solve_seconds = 0.0;  // set-up included
  std::size_t elements = 0;
  std::uint64_t links = 0;
  double residual = 0.0;
  bool converged = false;         // the solver's stop was met before its time ran out
  double path_bvh_seconds = 0.0;  // the path tracer's one set-up for all views
  std::vector<walkthrough_view> views;
  std::string error;  // why the run could not be made
};

// Runs the walkthrough of `s` through `views`, each judged against its
// reference (references[i]: a path-traced picture of views[i], at its size).
walkthrough_result run_walkthrough(const scene& s, const std::vector<camera>& views,
                                   const std::vector<image>& references, const walkthrough_settings& settings);

}  // namespace bounce
