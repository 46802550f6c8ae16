#include "cli/solve_command.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <tbb/parallel_for.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/console.h"
#include "cli/option_values.h"
#include "cli/scene_argument.h"
#include "cli/solver_options.h"
#include "cli/solver_stats.h"
#include "cli/time_limit.h"
#include "common/exit_code.h"
#include "measure/bench.h"
#include "mesh/patch_mesh.h"
#include "radiosity/progressive/reference_solver.h"
#include "radiosity/solve.h"
#include "radiosity/transfer/occlusion.h"

namespace bounce {
namespace {

using clock_type = std::chrono::steady_clock;

// Meshes and solves `s`, reports, and writes the files asked for.
int solve_scene(const scene& s, const solve_options& options) {
  const solver_settings& solver = options.solver;
  solve_setup setup;
  if (!start_command_solve(s, solver, setup)) return exit_input_error;
  std::string error;
  const patch_mesh& mesh = *setup.mesh;
  const refinement_pass& a_priori = setup.a_priori;
  say("mesh: %zu elements, %zu vertices, %zu shooting patches (max edge %g) in %.3f s\n", mesh.element_count(),
      mesh.vertex_count(), mesh.patch_count(), mesh.max_edge, setup.mesh_seconds);
  if (solver.adaptive.enabled)
    say("a priori refinement: %zu marks at contacts, %zu near emitters; %zu -> %zu elements\n", a_priori.contact,
        a_priori.emitter, a_priori.elements_before, a_priori.elements_after);
  warn_about_mesh(s, mesh);

  radiosity_solver& run = *setup.solver;
  const occlusion_scene& occlusion = *form_factors_of(run).occlusion;
  constexpr std::size_t baseline_rays = 2'000'000;
  if (options.ray_baseline)
    std::const_pointer_cast<occlusion_scene>(form_factors_of(run).occlusion)->record_segments(baseline_rays);
  auto last_print = clock_type::now();
  std::uint64_t steps_then = 0, rays_then = 0;
  const bool hierarchical = method_of(run) == solver_method::hierarchical;
  run_solver(run, with_time_left(solver.stop), [&](const radiosity_solver& st) {
    const auto now = clock_type::now();
    const double dt = std::chrono::duration<double>(now - last_print).count();
    if (dt < 1.0) return;
    if (hierarchical)
      say("steps %6llu  residual %9.5f%%  links %10llu  tolerance %.1e%s\n",
          static_cast<unsigned long long>(st.stats.steps), 100.0 * st.stats.remaining,
          static_cast<unsigned long long>(st.stats.links), st.stats.link_tolerance,
          st.stats.remaining_final ? "" : " (refining)");
    else
      say("shots %8llu  unshot %9.5f%%  %8.0f shots/s  %7.2f Mrays/s\n",
          static_cast<unsigned long long>(st.stats.steps), 100.0 * st.stats.remaining,
          double(st.stats.steps - steps_then) / dt, double(st.stats.rays - rays_then) / dt * 1e-6);
    std::fflush(stdout);
    last_print = now;
    steps_then = st.stats.steps;
    rays_then = st.stats.rays;
  });
  const solver_stats& st = run.stats;
  const patch_mesh& solved = solved_mesh(run);  // refined, with --adaptive or split elements
  const std::shared_ptr<const radiosity_snapshot> solution = make_snapshot(run);
  if (const progressive_state* progressive = progressive_of(run)) {
    for (const refinement_pass& pass : progressive->adaptive.history)
      say("refinement at unshot %.3f%%: %zu marked by radiosity difference, %zu on shadow edges; %zu -> %zu "
          "elements (+%zu vertices) in %.3f s\n",
          100.0 * pass.unshot_fraction, pass.gradient, pass.shadow, pass.elements_before, pass.elements_after,
          pass.new_vertices, pass.seconds);
    if (!progressive->adaptive.error.empty())
      std::fprintf(stderr, "warning: refinement stopped: %s\n", progressive->adaptive.error.c_str());
    if (solver.adaptive.enabled)
      say("adaptive mesh: %zu elements, %zu vertices (%zu elements before refinement while solving)\n",
          solved.element_count(), solved.vertex_count(), mesh.element_count());
    say("done: %llu shots, unshot %.6f%%, %.3f s, %llu rays (%.2f Mrays/s), power balance error %.2e\n",
        static_cast<unsigned long long>(st.steps), 100.0 * st.remaining, st.seconds,
        static_cast<unsigned long long>(st.rays), st.seconds > 0 ? double(st.rays) / st.seconds * 1e-6 : 0.0,
        balance_error(progressive->balance));
  } else if (const hierarchical_solver* h = hierarchical_of(run)) {
    say("done: hierarchical, %llu steps, residual %.6f%%, %.3f s, %zu links (%.1f MiB) at tolerance %.1e, "
        "%llu rays, %zu tree nodes%s\n",
        static_cast<unsigned long long>(st.steps), 100.0 * st.remaining, st.seconds, h->hierarchy.links.size(),
        double(h->hierarchy.links.size() * sizeof(hierarchy_link)) / (1 << 20), h->progress.tolerance,
        static_cast<unsigned long long>(st.rays), h->hierarchy.tree.nodes.size(),
        h->progress.closed ? ", closed scene: form factors normalised" : "");
    if (!h->hierarchy.mirror_links.empty())
      say("links through planar mirrors: %zu (%.1f MiB) over %zu mirror chains\n", h->hierarchy.mirror_links.size(),
          double(h->hierarchy.mirror_links.size() * sizeof(mirror_link)) / (1 << 20), h->hierarchy.chains.size());
  }
  warn_about_solve(s, run);

  nlohmann::json stats = solver_stats_json(s, solver, mesh, run, setup.mesh_seconds);

  if (options.reference) {
    reference_params rp;
    rp.form_factors = solver.form_factors;
    reference_solution ref;
    if (!solve_reference(s, solved, rp, ref, error)) {
      std::fprintf(stderr, "error: %s: %s\n", s.source.c_str(), error.c_str());
      return exit_input_error;
    }
    const double difference = vertex_relative_error(solution->radiosity, ref.radiosity).max;
    const double gs_difference = vertex_relative_error(ref.radiosity_gauss_seidel, ref.radiosity).max;
    say("reference: matrix %.3f s, LU %.3f s (residual %.2e), Gauss-Seidel %.3f s, %d iterations (residual "
        "%.2e, differs from LU by %.2e)\n",
        ref.seconds_matrix, ref.seconds_lu, ref.residual, ref.seconds_gauss_seidel, ref.gauss_seidel_iterations,
        ref.residual_gauss_seidel, gs_difference);
    say("progressive vs reference: max relative difference %.3e\n", difference);
    stats["reference"] = {{"residual_lu", ref.residual},
                          {"residual_gauss_seidel", ref.residual_gauss_seidel},
                          {"gauss_seidel_iterations", ref.gauss_seidel_iterations},
                          {"seconds_matrix", ref.seconds_matrix},
                          {"seconds_lu", ref.seconds_lu},
                          {"seconds_gauss_seidel", ref.seconds_gauss_seidel},
                          {"max_relative_difference", difference}};
  }
  if (options.ray_baseline && solver.form_factors.method != form_factor_method::raycast) {
    say("ray baseline: the hemicube casts no shadow rays\n");
  } else if (options.ray_baseline) {
    // The same segments, one rtcOccluded1 call each, on all cores: Embree's
    // own rate on exactly the solver's rays, with no form-factor work.
    const auto segments = occlusion.recorded_segments();
    const auto start = clock_type::now();
    std::atomic<std::size_t> blocked{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, segments.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::size_t local = 0;
                        for (std::size_t i = r.begin(); i < r.end(); ++i)
                          local += occlusion.occluded(segments[i].from, segments[i].to);
                        blocked += local;
                      });
    const double seconds = std::chrono::duration<double>(clock_type::now() - start).count();
    const double raw = double(segments.size()) / seconds * 1e-6;
    const double solver_rate = st.seconds > 0 ? double(st.rays) / st.seconds * 1e-6 : 0.0;
    say("ray baseline: rtcOccluded1 on %zu recorded solver rays: %.2f Mrays/s (%zu blocked); the solver's "
        "%.2f Mrays/s, form factors included, is %.0f%% of it\n",
        segments.size(), raw, blocked.load(), solver_rate, raw > 0 ? 100.0 * solver_rate / raw : 0.0);
    stats["ray_baseline"] = {
        {"rays", segments.size()}, {"embree_mrays_per_second", raw}, {"solver_mrays_per_second", solver_rate}};
  }
  if (!options.stats_path.empty() && !write_stats(options.stats_path, stats, error)) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return exit_input_error;
  }
  for (const auto& [path, settings] :
       {std::pair{options.ply_path, bake_settings{}}, {options.bake_path, options.bake}}) {
    if (path.empty()) continue;
    double exposure = 0.0;
    if (!write_bake(path, s, solved, *solution, settings, error, &exposure)) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return exit_input_error;
    }
    say("wrote %s (%zu vertices, %zu triangles; colours at exposure %.4g)\n", path.c_str(), solved.vertex_count(),
        solved.element_count(), exposure);
  }
  return exit_ok;
}

}  // namespace

void add_solve_options(CLI::App& command, solve_options& options) {
  add_scene_argument(command, options.scene);
  add_solver_options(command, options.solver);
  command.add_option("--ply", options.ply_path, "write the patch mesh with per-vertex radiosity as PLY");
  command.add_option("--stats", options.stats_path, "write solver statistics as JSON to this file");
  command.add_flag("--reference", options.reference,
                   "also solve the full matrix (small scenes) and report the difference");
  command.add_flag("--ray-baseline", options.ray_baseline,
                   "raycast: replay 2M of the solver's shadow rays through Embree's rtcOccluded1 and compare rates");
}

std::string check_solve_options(const CLI::App& command, solve_options& options) {
  if (std::string e = check_solver_options(command, options.solver); !e.empty()) return e;
  if (options.reference || options.ray_baseline) {
    // Both measure the progressive solver (against the matrix solution of
    // its own system, or Embree's raw rate on its rays).
    const std::string option = options.reference ? "--reference" : "--ray-baseline";
    if (command.count("--solver") && options.solver.method == solver_method::hierarchical)
      return option + " applies to --solver progressive only";
    if (command.count("--link-tolerance"))
      return "--link-tolerance applies to --solver hierarchical only (" + option + " measures the progressive solver)";
    options.solver.method = solver_method::progressive;
  }
  if (options.ray_baseline && options.solver.form_factors.method != form_factor_method::raycast)
    return "--ray-baseline applies to --method raycast only (the hemicube casts no shadow rays)";
  if (!options.ply_path.empty() && bake_format_of(options.ply_path) != bake_format::ply)
    return "--ply: expected a .ply file, got '" + options.ply_path + "'";
  return check_output_files({{"--ply", options.ply_path, false}, {"--stats", options.stats_path, false}});
}

int run_solve(const solve_options& options) {
  const setup_time_limit limit(options.solver.stop.seconds);  // loading and meshing count
  scene s;
  if (int code = load_for_command(
          options.scene, nullptr, s, nullptr,
          {{"--ply", options.ply_path}, {"--out", options.bake_path}, {"--stats", options.stats_path}});
      code != exit_ok)
    return code;
  return solve_scene(s, options);
}

}  // namespace bounce
