#include "measure/walkthrough.h"

#include <chrono>
#include <memory>

#include "measure/picture_judge.h"
#include "radiosity/solve.h"
#include "trace/radiosity_field.h"
#include "trace/ray_scene.h"
#include "trace/ray_tracer.h"

namespace bounce {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

walkthrough_result run_walkthrough(const scene& s, const std::vector<camera>& views,
                                   const std::vector<image>& references, const walkthrough_settings& settings) {
  walkthrough_result result;
  if (views.size() != references.size()) {
    result.error = "a reference picture per view is needed";
    return result;
  }
  // The one solve, view-independent: every view is drawn from it.
  const auto solve_start = std::chrono::steady_clock::now();
  solver_settings solver_settings = settings.solver;
  solver_settings.view.reset();
  solve_setup setup;
  if (!start_solve(s, solver_settings, setup, result.error)) return result;
  result.setup_seconds = seconds_since(solve_start);
  radiosity_solver& solver = *setup.solver;
  bool stopped = false;
  run_solver(solver, solver_settings.stop,
             [&](const radiosity_solver& r) { stopped = stop_reached(r, solver_settings.stop); });
  const std::shared_ptr<const radiosity_snapshot> solution = make_snapshot(solver);
  const patch_mesh& mesh = solved_mesh(solver);
  const radiosity_field field(mesh, solution->radiosity, solution->direct);
  result.solve_seconds = seconds_since(solve_start);
  result.elements = mesh.element_count();
  result.links = solver.stats.links;
  result.residual = solver.stats.remaining;
  result.converged =
      stopped && solver.stats.remaining_final && solver.stats.remaining <= solver_settings.stop.remaining;

  const auto bvh_start = std::chrono::steady_clock::now();
  const auto rays = std::make_shared<const ray_scene>(s);
  result.path_bvh_seconds = seconds_since(bvh_start);

  for (std::size_t i = 0; i < views.size(); ++i) {
    bench_truth truth;
    truth.picture = references[i];
    truth.downsample = settings.downsample;
    truth.exclude_above = emitter_threshold(s);
    truth.still_spp = settings.still_spp;
    camera view = views[i];
    view.width = references[i].width;
    view.height = references[i].height;
    const picture_judge judge(s, view, truth, rays);
    walkthrough_view v;

    trace_params drawn;
    drawn.spp = settings.still_spp;
    drawn.diffuse = diffuse_source::radiosity;
    const auto draw_start = std::chrono::steady_clock::now();
    const image picture = trace_image(s, view, *rays, &field, drawn);
    v.radiosity_seconds = seconds_since(draw_start);
    v.radiosity_error = judge.judge(picture).error;

    for (int spp = 1; spp <= settings.path_max_spp; spp *= 2) {
      trace_params path;
      path.method = integrator::path;
      path.spp = spp;
      path.seed = 2 + i;  // the references are traced with seed 1: independent noise
      const auto path_start = std::chrono::steady_clock::now();
      const image traced = trace_image(s, view, *rays, nullptr, path);
      v.path_seconds = seconds_since(path_start);
      v.path_spp = spp;
      v.path_error = judge.judge(traced).error;
      v.path_reached = v.path_error <= v.radiosity_error;
      if (v.path_reached) break;
    }
    result.views.push_back(v);
  }
  return result;
}

}  // namespace bounce
