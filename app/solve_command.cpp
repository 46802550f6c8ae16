#include "solve_command.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <tbb/parallel_for.h>
#include <nlohmann/json.hpp>

#include "console.h"
#include "measure/bench.h"
#include "mesh/patch_mesh.h"
#include "mesh/ply.h"
#include "radiosity/occlusion.h"
#include "radiosity/radiosity.h"
#include "radiosity/reference_solver.h"
#include "solver_stats.h"

namespace bounce {
namespace {

using clock_type = std::chrono::steady_clock;

}  // namespace

int run_solve(const scene& s, const solver_settings& solver, const solve_options& extra) {
  const auto mesh_start = clock_type::now();
  patch_mesh mesh;
  std::string error;
  refinement_pass a_priori;
  mesher_params mesher = mesher_params_for(solver, s);
  mesher.a_priori_report = &a_priori;
  if (!make_patch_mesh(s, mesher, mesh, error)) {
    std::fprintf(stderr, "error: %s: %s\n", s.source.c_str(), error.c_str());
    return exit_input_error;
  }
  const double mesh_seconds = std::chrono::duration<double>(clock_type::now() - mesh_start).count();
  say("mesh: %zu elements, %zu vertices, %zu shooting patches (max edge %g) in %.3f s\n", mesh.element_count(),
      mesh.vertex_count(), mesh.patch_count(), mesh.max_edge, mesh_seconds);
  if (solver.adaptive.enabled)
    say("a priori refinement: %zu marks at contacts, %zu near emitters; %zu -> %zu elements\n", a_priori.contact,
        a_priori.emitter, a_priori.elements_before, a_priori.elements_after);
  warn_about_mesh(s, mesh);

  auto state = make_radiosity_state(s, mesh, radiosity_params_for(solver));
  constexpr std::size_t baseline_rays = 2'000'000;
  if (extra.ray_baseline)
    std::const_pointer_cast<occlusion_scene>(state->form_factors.occlusion)->record_segments(baseline_rays);
  auto last_print = clock_type::now();
  std::uint64_t shots_then = 0, rays_then = 0;
  run_radiosity(*state, solver.stop, [&](const radiosity_state& st) {
    const auto now = clock_type::now();
    const double dt = std::chrono::duration<double>(now - last_print).count();
    if (dt < 1.0) return;
    if (st.hierarchy)
      say("steps %6llu  residual %9.5f%%  links %10llu  tolerance %.1e%s\n",
          static_cast<unsigned long long>(st.stats.shots), 100.0 * st.stats.unshot_fraction,
          static_cast<unsigned long long>(st.stats.links), st.stats.link_tolerance,
          st.stats.links_final ? "" : " (refining)");
    else
      say("shots %8llu  unshot %9.5f%%  %8.0f shots/s  %7.2f Mrays/s\n",
          static_cast<unsigned long long>(st.stats.shots), 100.0 * st.stats.unshot_fraction,
          double(st.stats.shots - shots_then) / dt, double(st.stats.rays - rays_then) / dt * 1e-6);
    std::fflush(stdout);
    last_print = now;
    shots_then = st.stats.shots;
    rays_then = st.stats.rays;
  });
  const radiosity_stats& st = state->stats;
  const power_balance& pb = state->balance;
  const patch_mesh& solved = *state->mesh;  // refined, with --adaptive
  for (const refinement_pass& pass : state->adaptive.history)
    say("refinement at unshot %.3f%%: %zu marked by radiosity difference, %zu on shadow edges; %zu -> %zu elements "
        "(+%zu vertices) in %.3f s\n",
        100.0 * pass.unshot_fraction, pass.gradient, pass.shadow, pass.elements_before, pass.elements_after,
        pass.new_vertices, pass.seconds);
  if (!state->adaptive.error.empty())
    std::fprintf(stderr, "warning: refinement stopped: %s\n", state->adaptive.error.c_str());
  if (solver.adaptive.enabled)
    say("adaptive mesh: %zu elements, %zu vertices (%zu elements before refinement while solving)\n",
        solved.element_count(), solved.vertex_count(), mesh.element_count());
  if (state->hierarchy) {
    const hierarchical_solver& h = *state->hierarchy;
    say("done: hierarchical, %llu steps, residual %.6f%%, %.3f s, %zu links (%.1f MiB) at tolerance %.1e, "
        "%llu rays, %zu tree nodes%s\n",
        static_cast<unsigned long long>(st.shots), 100.0 * st.unshot_fraction, st.seconds, h.links.size(),
        double(h.links.size() * sizeof(hierarchy_link)) / (1 << 20), h.progress.tolerance,
        static_cast<unsigned long long>(st.rays), h.tree.nodes.size(),
        h.progress.closed ? ", closed scene: form factors normalised" : "");
    if (!h.mirror_links.empty())
      say("links through planar mirrors: %zu (%.1f MiB) over %zu mirror chains\n", h.mirror_links.size(),
          double(h.mirror_links.size() * sizeof(mirror_link)) / (1 << 20), h.chains.size());
    if (!h.progress.warning.empty()) std::fprintf(stderr, "warning: %s\n", h.progress.warning.c_str());
  } else {
    say("done: %llu shots, unshot %.6f%%, %.3f s, %llu rays (%.2f Mrays/s), power balance error %.2e\n",
        static_cast<unsigned long long>(st.shots), 100.0 * st.unshot_fraction, st.seconds,
        static_cast<unsigned long long>(st.rays), st.seconds > 0 ? double(st.rays) / st.seconds * 1e-6 : 0.0,
        balance_error(pb));
  }

  nlohmann::json stats = solver_stats_json(s, solver, mesh, *state, mesh_seconds);

  if (extra.reference) {
    reference_params rp;
    rp.form_factors = solver.form_factors;
    reference_solution ref;
    if (!solve_reference(s, solved, rp, ref, error)) {
      std::fprintf(stderr, "error: %s: %s\n", s.source.c_str(), error.c_str());
      return exit_input_error;
    }
    const double difference = vertex_relative_error(state->radiosity, ref.radiosity).max;
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
  if (extra.ray_baseline && solver.form_factors.method != form_factor_method::raycast) {
    say("ray baseline: the hemicube casts no shadow rays\n");
  } else if (extra.ray_baseline) {
    // The same segments, one rtcOccluded1 call each, on all cores: Embree's
    // own rate on exactly the solver's rays, with no form-factor work.
    const auto segments = state->form_factors.occlusion->recorded_segments();
    const auto start = clock_type::now();
    std::atomic<std::size_t> blocked{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, segments.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::size_t local = 0;
                        for (std::size_t i = r.begin(); i < r.end(); ++i)
                          local += state->form_factors.occlusion->occluded(segments[i].from, segments[i].to);
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
  if (!extra.stats_path.empty() && !write_stats(extra.stats_path, stats, error)) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return exit_input_error;
  }
  if (!extra.ply_path.empty()) {
    if (!write_ply(extra.ply_path, solved, state->radiosity, error)) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return exit_input_error;
    }
    say("wrote %s\n", extra.ply_path.c_str());
  }
  return exit_ok;
}

}  // namespace bounce
