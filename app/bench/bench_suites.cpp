#include "bench/bench_suites.h"

#include <cstdio>
#include <initializer_list>
#include <stdexcept>
#include <utility>

#include "scene/procedural.h"
#include "scene/scene_io.h"

namespace bounce {
namespace {

const bench_scene bench_scenes[] = {
    {"cornell", default_scene_path, exact_kind::none},
    {"occluders", "embedded:bench/occluders.json", exact_kind::none},
    {"furnace", "embedded:bench/furnace.json", exact_kind::furnace},
    {"furnace-0.99", "embedded:bench/furnace_099.json", exact_kind::furnace},
    {"sphere", "embedded:bench/sphere.json", exact_kind::sphere_interior},
    {"squares-perpendicular", "embedded:bench/squares_perpendicular.json", exact_kind::emitter_receiver},
    {"squares-parallel", "embedded:bench/squares_parallel.json", exact_kind::emitter_receiver},
    // Built in code (procedural.h), measured against path-traced pictures.
    {"box-room-1", nullptr, exact_kind::none},
    {"box-room-10", nullptr, exact_kind::none},
    {"box-room-open-10", nullptr, exact_kind::none},
    {"box-room-30", nullptr, exact_kind::none},
    {"box-room-60", nullptr, exact_kind::none},
    {"interior-10k", nullptr, exact_kind::none},
    {"interior-30k", nullptr, exact_kind::none},
    {"interior-100k", nullptr, exact_kind::none},
    {"interior-300k", nullptr, exact_kind::none},
    {"interior-1m", nullptr, exact_kind::none},
};

// A progressive run: `rays` shadow rays (raycast) or a hemicube of
// `hemicube` pixels, at `edge`, patches of `patch_factor` x edge (0:
// elements shoot).
bench_case progressive_case(const std::string& scene, form_factor_method method, int rays, int hemicube, double edge,
                            double patch_factor, double until, double max_seconds) {
  bench_case c;
  c.scene = scene;
  c.settings.method = solver_method::progressive;
  c.settings.form_factors.method = method;
  c.settings.form_factors.shadow_rays = rays;
  c.settings.form_factors.hemicube_resolution = hemicube;
  c.settings.max_edge = edge;
  c.settings.patch_edge = patch_factor * edge;
  c.settings.stop.remaining = until;
  c.settings.stop.seconds = max_seconds;
  return c;
}

// Progressive runs of one scene: every method setting at every density.
void add_progressive(suite_plan& plan, const std::string& scene, std::initializer_list<double> edges,
                     std::initializer_list<int> rays, std::initializer_list<int> hemicubes, double max_seconds,
                     double until = 1e-3) {
  for (double edge : edges) {
    for (int r : rays)
      plan.cases.push_back(progressive_case(scene, form_factor_method::raycast, r, 256, edge, 4.0, until, max_seconds));
    for (int h : hemicubes)
      plan.cases.push_back(progressive_case(scene, form_factor_method::hemicube, 16, h, edge, 4.0, until, max_seconds));
  }
}

// Adaptive meshing on the Cornell box from coarse starting meshes, 16 rays,
// elements shooting (the --adaptive default: shooters refine with them).
void add_adaptive(suite_plan& plan, std::initializer_list<double> edges, std::initializer_list<double> tolerances,
                  double max_seconds, double patch_factor = 0.0) {
  for (double edge : edges)
    for (double tolerance : tolerances) {
      bench_case c =
          progressive_case("cornell", form_factor_method::raycast, 16, 256, edge, patch_factor, 1e-3, max_seconds);
      c.settings.adaptive.enabled = true;
      c.settings.adaptive.tolerance = tolerance;
      plan.cases.push_back(c);
    }
}

void add_reference(suite_plan& plan, const std::string& scene, double edge) {
  bench_case c;
  c.scene = scene;
  c.kind = bench_solver::reference;
  c.settings.method = solver_method::progressive;  // meshed as the progressive solver's elements
  c.settings.max_edge = edge;
  plan.cases.push_back(c);
}

void add_path(suite_plan& plan, const std::string& scene, double max_seconds) {
  bench_case c;
  c.scene = scene;
  c.kind = bench_solver::path_tracer;
  c.settings.stop.seconds = max_seconds;
  plan.cases.push_back(c);
}

// A hierarchical run: the scene's hierarchical mesh (or elements of
// `edge`), links refined down to `tolerance`, stopping at `until` of the
// emitted power left as residual or after `max_seconds`.
bench_case hierarchical_case(const std::string& scene, double tolerance, double max_seconds, double until = 1e-3,
                             double edge = 0.0) {
  bench_case c;
  c.scene = scene;
  c.settings.method = solver_method::hierarchical;
  c.settings.link_tolerance = tolerance;
  c.settings.max_edge = edge;
  c.settings.stop.remaining = until;
  c.settings.stop.seconds = max_seconds;
  return c;
}

// A run with the solver's own defaults (mesh, patches, form factors, link
// tolerance) but the bench's stop: 1e-3 of the power left, or `max_seconds`.
bench_case default_case(const std::string& scene, solver_method method, double max_seconds, int threads = 0) {
  bench_case c;
  c.scene = scene;
  c.settings = solver_settings{};
  c.settings.method = method;
  c.settings.stop.remaining = 1e-3;
  c.settings.stop.seconds = max_seconds;
  c.threads = threads;
  return c;
}

void add_growth(suite_plan& plan, std::initializer_list<double> edges, double max_seconds) {
  for (double edge : edges) {
    bench_case c = progressive_case("cornell", form_factor_method::raycast, 16, 256, edge, 4.0, 0.01, max_seconds);
    c.growth = true;
    plan.cases.push_back(c);
  }
}

}  // namespace

const bench_scene& find_scene(const std::string& name) {
  for (const bench_scene& s : bench_scenes)
    if (name == s.name) return s;
  throw std::logic_error("bench: no scene " + name);
}

suite_plan make_suite(const std::string& suite) {
  suite_plan plan;
  if (suite == "quick") {
    // A smoke run: every scene and method once, small meshes, short runs.
    add_progressive(plan, "cornell", {150}, {4, 16}, {64}, 3.0);
    add_progressive(plan, "cornell", {100}, {16}, {}, 2.0);
    add_reference(plan, "cornell", 150);
    add_path(plan, "cornell", 1.0);
    add_progressive(plan, "occluders", {0.5}, {16}, {}, 2.0);
    add_path(plan, "occluders", 0.5);
    add_progressive(plan, "furnace", {0.5}, {16}, {64}, 2.0);
    add_reference(plan, "furnace", 0.5);
    add_progressive(plan, "furnace-0.99", {0.5}, {16}, {}, 2.0);
    add_progressive(plan, "sphere", {0.5}, {16}, {}, 2.0);
    add_progressive(plan, "squares-perpendicular", {0.1}, {16}, {64}, 2.0);
    add_progressive(plan, "squares-parallel", {0.1}, {16}, {}, 2.0);
    add_growth(plan, {150, 100}, 5.0);
    add_adaptive(plan, {150}, {0.5}, 1.5);
    // Coarser links than the default: the smoke run checks that every
    // output is written, not the default's accuracy (the hierarchical suite does).
    const double tolerance = 1e-4;
    plan.cases.push_back(hierarchical_case("cornell", tolerance, 3.0));
    plan.cases.push_back(hierarchical_case("furnace-0.99", tolerance, 2.0));
    plan.cases.push_back(hierarchical_case("occluders", tolerance, 2.0));
    plan.picture_size = 64;
    plan.reference_spp = 256;
    return plan;
  }
  if (suite == "hierarchical") {
    // The hierarchical solver against the baselines where issue-sized
    // targets are set: the Cornell box at 128 x 128 (against a 4096-spp
    // reference) over link tolerances, the progressive solver's defaults
    // and the path tracer; the rho = 0.99 furnace at 0.05 edges to 1e-5.
    for (double tolerance : {3e-5, 1e-5, 3e-6, 1e-6})
      plan.cases.push_back(hierarchical_case("cornell", tolerance, 25.0));
    plan.cases.push_back(default_case("cornell", solver_method::progressive, 25.0));
    add_path(plan, "cornell", 20.0);
    plan.cases.push_back(hierarchical_case("furnace-0.99", solver_settings{}.link_tolerance, 60.0, 1e-5, 0.05));
    bench_case furnace = default_case("furnace-0.99", solver_method::progressive, 30.0);
    furnace.settings.max_edge = 0.05;
    furnace.settings.stop.remaining = 1e-5;
    plan.cases.push_back(furnace);
    plan.picture_size = 128;
    plan.reference_spp = 4096;
    return plan;
  }
  if (suite == "scale") {
    // Procedural scenes from 10k to 1M triangles: how each solver's time to
    // an error grows with the scene. The progressive solver is given 60 s
    // on the smaller ones (it does not converge on the larger: that is the
    // point); the hierarchical solver runs on all, with its defaults.
    const std::pair<const char*, double> hierarchical_runs[] = {
        {"box-room-60", 30.0},   {"interior-10k", 15.0},  {"interior-30k", 20.0},
        {"interior-100k", 30.0}, {"interior-300k", 45.0}, {"interior-1m", 60.0},
    };
    for (const auto& [scene, seconds] : hierarchical_runs)
      plan.cases.push_back(default_case(scene, solver_method::hierarchical, seconds));
    for (const char* scene : {"box-room-60", "interior-10k", "interior-30k", "interior-100k"})
      plan.cases.push_back(default_case(scene, solver_method::progressive, 60.0));
    // The path tracer on two of them: its error against the reference at
    // doubling sample counts also shows the reference's own noise.
    add_path(plan, "box-room-60", 15.0);
    add_path(plan, "interior-10k", 15.0);
    // Speed-up with threads: the same run on 1 and on 2 threads.
    for (int threads : {1, 2})
      plan.cases.push_back(default_case("interior-100k", solver_method::hierarchical, 120.0, threads));
    plan.picture_size = 128;
    plan.reference_spp = 512;
    return plan;
  }
  if (suite == "clutter") {
    // Rooms of boxes, where coarse transfers lose light: the mean per
    // material (ceiling, walls, floor, boxes) against the path tracer's,
    // from one box (no bias expected) to a 30 x 30 grid, closed and open
    // (no wall behind the camera, the closed scene's normaliser off), with each
    // solver's defaults, and the hierarchical solver at lower tolerances
    // on the 10 x 10 grid to show what the defaults leave.
    for (const char* scene : {"box-room-1", "box-room-10", "box-room-open-10", "box-room-30"}) {
      plan.cases.push_back(default_case(scene, solver_method::hierarchical, 60.0));
      plan.cases.push_back(default_case(scene, solver_method::progressive, 60.0));
      add_path(plan, scene, 15.0);
    }
    for (double tolerance : {1e-6, 1e-7}) plan.cases.push_back(hierarchical_case("box-room-10", tolerance, 120.0));
    plan.picture_size = 128;
    plan.reference_spp = 1024;
    return plan;
  }
  if (suite == "adaptive") {
    // Adaptive against uniform meshes on the Cornell box, 16 rays: the
    // full suite's Cornell picture and reference.
    add_progressive(plan, "cornell", {100, 60, 40, 30}, {16}, {}, 25.0);
    // 15 mm given the time to converge (to 1e-3 unshot: about 100 s), so
    // that the best uniform error is the mesh's, not the time limit's.
    plan.cases.push_back(progressive_case("cornell", form_factor_method::raycast, 16, 256, 15, 4.0, 1e-3, 150.0));
    add_adaptive(plan, {100, 60}, {0.5, 1.0}, 40.0);
    plan.picture_size = 128;
    plan.reference_spp = 4096;
    return plan;
  }
  // full
  add_adaptive(plan, {100, 60}, {0.5}, 25.0);
  add_progressive(plan, "cornell", {100, 60, 30}, {4, 16, 64}, {}, 25.0);
  add_progressive(plan, "cornell", {40}, {4, 16}, {}, 25.0);  // 40 mm: the scene's default element size
  add_progressive(plan, "cornell", {60}, {}, {64, 128, 256}, 25.0);
  add_progressive(plan, "cornell", {30}, {}, {128}, 25.0);
  plan.cases.push_back(progressive_case("cornell", form_factor_method::raycast, 16, 256, 60, 0.0, 1e-3, 25.0));
  add_reference(plan, "cornell", 100);
  add_reference(plan, "cornell", 60);
  add_path(plan, "cornell", 40.0);
  add_progressive(plan, "occluders", {0.27, 0.135}, {4, 16}, {}, 20.0);
  add_progressive(plan, "occluders", {0.27}, {}, {128}, 20.0);
  add_path(plan, "occluders", 20.0);
  add_progressive(plan, "furnace", {0.5, 0.25}, {4, 16}, {64, 256}, 10.0);
  add_reference(plan, "furnace", 0.5);
  add_progressive(plan, "furnace-0.99", {0.5}, {16}, {}, 40.0);
  add_reference(plan, "furnace-0.99", 0.5);
  add_progressive(plan, "sphere", {0.5, 0.25}, {16}, {}, 15.0);
  add_progressive(plan, "sphere", {0.25}, {}, {128}, 15.0);
  add_reference(plan, "sphere", 0.5);
  add_progressive(plan, "squares-perpendicular", {0.1, 0.05}, {1, 16}, {64, 256}, 10.0);
  add_progressive(plan, "squares-parallel", {0.1, 0.05}, {16}, {256}, 10.0);
  for (double tolerance : {3e-5, 1e-5, 3e-6, 1e-6}) plan.cases.push_back(hierarchical_case("cornell", tolerance, 25.0));
  plan.cases.push_back(hierarchical_case("furnace-0.99", solver_settings{}.link_tolerance, 40.0, 1e-5));
  plan.cases.push_back(hierarchical_case("occluders", solver_settings{}.link_tolerance, 20.0));
  plan.cases.push_back(hierarchical_case("sphere", solver_settings{}.link_tolerance, 15.0));
  plan.cases.push_back(progressive_case("cornell", form_factor_method::raycast, 4, 256, 15, 4.0, 1e-3, 60.0));
  add_growth(plan, {70, 30, 15, 7.5}, 90.0);
  plan.picture_size = 128;
  plan.reference_spp = 4096;
  return plan;
}

std::string solver_name(const bench_case& c) {
  switch (c.kind) {
    case bench_solver::radiosity:
      return std::string(name_of(c.settings.method));
    case bench_solver::reference:
      return "reference";
    case bench_solver::path_tracer:
      return "path";
  }
  return "";
}

std::string method_label(const bench_case& c) {
  if (c.kind == bench_solver::path_tracer) return "path";
  if (c.kind == bench_solver::radiosity && c.settings.method == solver_method::hierarchical) return "links";
  return std::string(name_of(c.settings.form_factors.method));
}

// The label of a curve: its solver and method with the settings that
// matter for it, e.g. "progressive raycast 16, edge 60, element shooters",
// "hierarchical, link tolerance 1e-05, default mesh, 1 thread".
std::string curve_label(const bench_case& c, const std::string& curve_method) {
  if (c.kind == bench_solver::path_tracer) return "path tracer";
  const bool progressive = c.kind == bench_solver::radiosity && c.settings.method == solver_method::progressive;
  const bool hierarchical = c.kind == bench_solver::radiosity && !progressive;
  const form_factor_params& ff = c.settings.form_factors;
  std::string setting;
  char buffer[200];
  if (progressive)
    setting = " " + std::to_string(ff.method == form_factor_method::hemicube ? ff.hemicube_resolution : ff.shadow_rays);
  if (hierarchical) {
    std::snprintf(buffer, sizeof buffer, ", link tolerance %g", c.settings.link_tolerance);
    setting = buffer;
  }
  std::string details;
  if (c.settings.max_edge > 0.0) {
    std::snprintf(buffer, sizeof buffer, ", edge %g", c.settings.max_edge);
    details = buffer;
  } else {
    details = ", default mesh";
  }
  if (progressive && c.settings.patch_edge == 0.0) details += ", element shooters";
  if (c.settings.adaptive.enabled) {
    std::snprintf(buffer, sizeof buffer, ", adaptive %g", c.settings.adaptive.tolerance);
    details += buffer;
  }
  if (hierarchical && c.settings.stop.remaining != bench_case{}.settings.stop.remaining) {
    std::snprintf(buffer, sizeof buffer, ", to %g", c.settings.stop.remaining);
    details += buffer;
  }
  if (c.threads > 0) details += c.threads == 1 ? ", 1 thread" : ", " + std::to_string(c.threads) + " threads";
  if (c.growth) details += ", growth";
  std::string base = curve_method;
  const std::size_t plus = base.find(" + ");
  const std::string suffix = plus == std::string::npos ? "" : base.substr(plus);
  if (plus != std::string::npos) base.resize(plus);
  // The progressive solver's curves are named for their form-factor method: the solver's name goes first.
  return (progressive ? "progressive " : "") + base + setting + details + suffix;
}

bool load_bench_scene(const bench_case& c, int picture_size, scene& s, std::string& error) {
  const bench_scene& b = find_scene(c.scene);
  if (!b.path) {
    if (!make_procedural_scene(b.name, s, error)) return false;
  } else {
    load_report report;
    if (!load_scene(b.path, s, report)) {
      error = report.error;
      return false;
    }
  }
  s.view.width = s.view.height = picture_size;
  return true;
}

}  // namespace bounce
