#include "measure/bench.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "measure/run_clock.h"
#include "radiosity/progressive/reference_solver.h"
#include "radiosity/solve.h"
#include "radiosity/solver.h"

namespace bounce {
namespace {

// Compares per-vertex solutions with the closed form.
struct vertex_judge {
  const scene& s;
  exact_kind kind;
  std::vector<rgb> exact;
  double exact_power = 0.0;
  const patch_mesh* exact_for = nullptr;  // adaptive meshing changes the mesh: the exact values follow
  std::size_t exact_vertices = 0;

  vertex_judge(const scene& source, exact_kind k) : s(source), kind(k) {}

  void judge(const patch_mesh& mesh, std::span<const rgb> radiosity, bench_point& p) {
    if (exact_for != &mesh || exact_vertices != mesh.vertex_count()) {  // (a new mesh may reuse an address)
      exact = exact_vertex_radiosity(kind, s, mesh);
      exact_power = channel_sum(exact_reflected_power(kind, s, mesh));
      exact_for = &mesh;
      exact_vertices = mesh.vertex_count();
    }
    const vertex_error e = vertex_relative_error(radiosity, exact);
    p.error = e.rmse;
    p.max_error = e.max;
    p.power_error = std::abs(channel_sum(reflected_power(mesh, radiosity)) / exact_power - 1.0);
  }
};

bench_result run_radiosity_solver(const scene& s, const bench_setting& setting, const bench_truth& truth) {
  bench_result result;
  run_clock clock;
  solve_setup setup;
  if (!start_solve(s, setting.solver, setup, result.error)) return result;
  radiosity_solver& solver = *setup.solver;
  result.setup_seconds = clock.wall();
  result.elements = setup.mesh->element_count();
  result.vertices = setup.mesh->vertex_count();
  result.patches = setup.mesh->patch_count();

  std::unique_ptr<picture_judge> pictures;
  std::unique_ptr<vertex_judge> vertices;
  if (setting.measure_error) {
    clock.exclude([&] {
      if (truth.exact == exact_kind::none)
        pictures = std::make_unique<picture_judge>(s, s.view, truth);
      else
        vertices = std::make_unique<vertex_judge>(s, truth.exact);
    });
  }
  const bool hierarchical = setting.solver.method == solver_method::hierarchical;
  // The hierarchical solver's curve is named for it: it makes its own links
  // and form factors; the progressive solver's for its form-factor method.
  const std::string method(hierarchical ? name_of(setting.solver.method) : name_of(setting.solver.form_factors.method));
  result.curves.push_back({method, {}});
  if (pictures) result.curves.push_back({method + " + two-pass", {}});

  auto record = [&] {
    bench_point p;
    p.seconds = clock.wall();
    p.cpu_seconds = clock.cpu();
    p.steps = solver.stats.steps;
    p.rays = solver.stats.rays;
    p.remaining = solver.stats.remaining;
    // The hierarchical solver keeps no shooting balance: its residual is its remaining fraction.
    const progressive_state* progressive = progressive_of(solver);
    p.balance_error = progressive ? balance_error(progressive->balance) : not_measured;
    const patch_mesh& mesh = solved_mesh(solver);  // refined, with adaptive meshing
    p.elements = mesh.element_count();
    clock.exclude([&] {
      const std::shared_ptr<const radiosity_snapshot> solution = make_snapshot(solver);
      if (vertices) vertices->judge(mesh, solution->radiosity, p);
      if (!pictures) return;
      bench_point two_pass = p;
      const auto view = pictures->judge_solution(mesh, solution->radiosity, {}, diffuse_source::radiosity);
      p.error = view.error;
      p.max_error = view.max_error;
      p.surfaces = view.surfaces;
      const auto still =
          pictures->judge_solution(mesh, solution->radiosity, solution->direct, diffuse_source::traced_direct);
      two_pass.seconds += still.seconds;
      two_pass.cpu_seconds += still.cpu_seconds;
      two_pass.error = still.error;
      two_pass.max_error = still.max_error;
      two_pass.surfaces = still.surfaces;
      result.curves[1].points.push_back(two_pass);
    });
    result.curves[0].points.push_back(p);
  };

  // Stops spaced by a factor in time, so that a run of any length gives a
  // few dozen points evenly on the log-log plot.
  constexpr double stop_spacing = 1.25;
  double next_stop = 0.0;
  bool stopped = false;
  run_solver(solver, setting.solver.stop, [&](const radiosity_solver&) {
    const double t = clock.wall();
    if (std::isnan(result.first_picture_seconds) && all_emission_out(solver)) result.first_picture_seconds = t;
    stopped = stop_reached(solver, setting.solver.stop);
    if (!stopped && t < next_stop) return;
    record();
    next_stop = std::max(t * stop_spacing, t + 1e-3);
  });
  if (!stopped) record();  // the solver ran out of work: the last point
  if (solver.stats.steps > 0) result.seconds_per_step = solver.stats.seconds / double(solver.stats.steps);
  if (hierarchical) {
    result.links = solver.stats.links;
    result.link_tolerance = solver.stats.link_tolerance;
    result.links_final = solver.stats.remaining_final;
  }
  result.elements = solved_mesh(solver).element_count();  // adaptive: the refined mesh's
  result.vertices = solved_mesh(solver).vertex_count();
  return result;
}

bench_result run_reference(const scene& s, const bench_setting& setting, const bench_truth& truth) {
  bench_result result;
  run_clock clock;
  patch_mesh mesh;
  if (!make_patch_mesh(s, mesher_params_for(setting.solver, s), mesh, result.error)) return result;
  result.elements = mesh.element_count();
  result.vertices = mesh.vertex_count();
  result.patches = mesh.element_count();
  const double mesh_seconds = clock.wall();
  reference_params params;
  params.form_factors = setting.solver.form_factors;
  reference_solution solution;
  if (!solve_reference(s, mesh, params, solution, result.error)) return result;
  result.setup_seconds = mesh_seconds + solution.seconds_matrix;

  std::unique_ptr<picture_judge> pictures;
  std::unique_ptr<vertex_judge> vertices;
  if (setting.measure_error) {
    if (truth.exact == exact_kind::none)
      pictures = std::make_unique<picture_judge>(s, s.view, truth);
    else
      vertices = std::make_unique<vertex_judge>(s, truth.exact);
  }
  auto point = [&](const std::vector<rgb>& radiosity, double solve_seconds, double residual) {
    bench_point p;
    p.seconds = result.setup_seconds + solve_seconds;
    p.cpu_seconds = not_measured;  // one process runs both; the run's CPU total is reported
    p.rays = solution.rays;
    p.residual = residual;
    if (vertices) vertices->judge(mesh, radiosity, p);
    if (pictures) {
      const auto v = pictures->judge_solution(mesh, radiosity, {}, diffuse_source::radiosity);
      p.error = v.error;
      p.max_error = v.max_error;
      p.surfaces = v.surfaces;
    }
    return p;
  };
  result.curves.push_back({"reference-lu", {point(solution.radiosity, solution.seconds_lu, solution.residual)}});
  result.curves.push_back(
      {"gauss-seidel",
       {point(solution.radiosity_gauss_seidel, solution.seconds_gauss_seidel, solution.residual_gauss_seidel)}});
  return result;
}

bench_result run_path(const scene& s, const bench_setting& setting, const bench_truth& truth) {
  bench_result result;
  if (truth.exact != exact_kind::none) {
    result.error = "the path tracer is measured on pictures; this scene is measured per vertex";
    return result;
  }
  run_clock clock;
  picture_judge pictures(s, s.view, truth);
  result.setup_seconds = clock.wall();  // the ray-tracing BVH
  const double setup_cpu = clock.cpu();
  result.curves.push_back({"path", {}});
  double spent = 0.0;
  for (int spp = 1; spp <= setting.path_max_spp && spent < setting.solver.stop.seconds; spp *= 2) {
    trace_params params;
    params.method = integrator::path;
    params.spp = spp;
    params.seed = 2;  // the reference is traced with seed 1: independent noise
    trace_stats stats;
    const double c0 = cpu_seconds();
    const image picture = trace_image(s, s.view, pictures.rays(), nullptr, params, nullptr, &stats);
    bench_point p;
    p.cpu_seconds = setup_cpu + cpu_seconds() - c0;  // each picture is its own run: set-up plus its trace
    p.seconds = result.setup_seconds + stats.seconds;
    p.rays = stats.primary_rays + stats.shadow_rays + stats.secondary_rays;
    const auto v = pictures.judge(picture);
    p.error = v.error;
    p.max_error = v.max_error;
    p.surfaces = v.surfaces;
    result.curves[0].points.push_back(p);
    spent += stats.seconds;
  }
  return result;
}

}  // namespace

bench_result run_bench(const scene& s, const bench_setting& setting, const bench_truth& truth) {
  switch (setting.kind) {
    case bench_solver::radiosity:
      return run_radiosity_solver(s, setting, truth);
    case bench_solver::reference:
      return run_reference(s, setting, truth);
    case bench_solver::path_tracer:
      return run_path(s, setting, truth);
  }
  return {};
}

}  // namespace bounce
