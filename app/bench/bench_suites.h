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
  const char* path;  // nullptr: built by make_procedural_scene(name) (procedural.h)
  exact_kind exact;
};

// One run of the suite: a scene, a solver and its setting.
struct bench_case {
  std::string scene;
  bench_solver kind = bench_solver::radiosity;
  // Solver (settings.method: the program's default, hierarchical, unless
  // set), mesh (patch_edge: 0, elements shoot), form factors, adaptive
  // meshing, link tolerance, stop.
  solver_settings settings = [] {
    solver_settings d;
    d.patch_edge = 0.0;
    d.stop.remaining = 1e-3;
    d.stop.seconds = 10.0;
    return d;
  }();
  bool growth = false;  // timings and memory only, for the growth with element count
  int threads = 0;      // the run's thread limit; 0: the bench's --threads (0 there: every core)
};

struct suite_plan {
  std::vector<bench_case> cases;
  int picture_size = 64;     // bench pictures are picture_size^2
  int reference_spp = 1024;  // path-traced reference
};

// The bench scene named `name` (one of the suites' scene names).
const bench_scene& find_scene(const std::string& name);

// The cases of a suite: "quick", "hierarchical", "clutter", "adaptive", "scale" or "full" (anything else).
suite_plan make_suite(const std::string& suite);

// Names for reports: the solver (hierarchical, progressive, reference,
// path), the method, and a curve's label (its solver and method with the
// setting that matters for it).
std::string solver_name(const bench_case& c);
std::string method_label(const bench_case& c);
std::string curve_label(const bench_case& c, const std::string& curve_method);

// Loads a case's scene with its camera at the suite's picture size.
bool load_bench_scene(const bench_case& c, int picture_size, scene& s, std::string& error);

}  // namespace bounce
