// The bench's suites: its scenes (with the truth each is measured
// against) and the plan of each suite, scenes x methods x densities, as
// cases that `bounce bench` runs one child process each.
#pragma once

#include <string>
#include <vector>

#include "measure/bench.h"
#include "radiosity/solver_settings.h"
#include "scene/scene.h"

namespace bounce {

struct bench_scene {
  const char* name;
  const char* path;
  exact_kind exact;
};

// One run of the suite: a scene, a solver and its setting.
struct bench_case {
  std::string scene;
  bench_solver kind = bench_solver::progressive;
  // Mesh (patch_edge: 0, elements shoot), form factors, adaptive meshing, stop.
  solver_settings settings = [] {
    solver_settings d;
    d.patch_edge = 0.0;
    d.stop.unshot_fraction = 1e-3;
    d.stop.seconds = 10.0;
    return d;
  }();
  bool growth = false;  // timings and memory only, for the growth with element count
};

struct suite_plan {
  std::vector<bench_case> cases;
  int picture_size = 64;     // bench pictures are picture_size^2
  int reference_spp = 1024;  // path-traced reference
};

// The bench scene named `name` (one of the suites' scene names).
const bench_scene& find_scene(const std::string& name);

// The cases of a suite: "quick", "adaptive" or "full" (anything else).
suite_plan make_suite(const std::string& suite);

// Names for reports: the solver, the method, and a curve's label (its
// method with the setting that matters for it).
const char* solver_name(bench_solver s);
std::string method_label(const bench_case& c);
std::string curve_label(const bench_case& c, const std::string& curve_method);

// Loads a case's scene with its camera at the suite's picture size.
bool load_bench_scene(const bench_case& c, int picture_size, scene& s, std::string& error);

}  // namespace bounce
