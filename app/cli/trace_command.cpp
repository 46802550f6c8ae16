#include "cli/trace_command.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <future>
#include <memory>

#include <tbb/parallel_for.h>
#include <CLI/CLI.hpp>

#include "cli/console.h"
#include "cli/option_values.h"
#include "cli/scene_argument.h"
#include "cli/solver_options.h"
#include "cli/solver_stats.h"
#include "cli/time_limit.h"
#include "common/exit_code.h"
#include "image/picture_file.h"
#include "mesh/patch_mesh.h"
#include "radiosity/solve.h"
#include "scene/camera_math.h"
#include "scene/reader_support.h"
#include "scene/scene_info.h"
#include "trace/photon_map.h"
#include "trace/radiosity_field.h"
#include "trace/ray_tracer.h"

namespace bounce {

// Each caustic photon kept takes 104 bytes, and tracing 50 million takes
// minutes on a laptop: a count beyond is a mistake, not a wish (2^31 of
// them would need 220 GB).
constexpr std::uint64_t max_photons = 50'000'000;
namespace {

using clock_type = std::chrono::steady_clock;

struct solved {
  solver_settings settings;  // what it was solved with (the coarse pass has its own)
  solve_setup setup;
  std::shared_ptr<const radiosity_snapshot> solution;
};

// Meshes and runs the solver to the options' criterion.
bool solve(const scene& s, const solver_settings& solver, solved& out) {
  out.settings = solver;
  if (!start_command_solve(s, solver, out.setup)) return false;
  warn_about_mesh(s, *out.setup.mesh);
  progress_line progress("solving");
  const solver_method method = method_of(*out.setup.solver);
  const stop_criterion stop = with_time_left(solver.stop);
  run_solver(*out.setup.solver, stop, [&](const radiosity_solver& st) {
    progress.update(solve_progress(st.stats.remaining, stop.remaining, st.stats.seconds, stop.seconds),
                    remaining_text(method, st.stats.remaining));
  });
  progress.done();
  warn_about_solve(s, *out.setup.solver);
  out.solution = make_snapshot(*out.setup.solver);
  return true;
}

}  // namespace

void add_trace_options(CLI::App& command, trace_options& options) {
  add_scene_argument(command, options.scene);
  add_solver_options(command, options.solver);
  add_view_independent_option(command, options.view_independent);
  add_camera_options(command, options.camera);
  command
      .add_option("--out", options.out_path,
                  "the still; the extension picks the format: .png (radiance x exposure, sRGB), or .pfm, .exr, .hdr "
                  "(linear radiance, unscaled)")
      ->capture_default_str();
  command.add_option("--pfm", options.pfm_path, "also write the still in linear radiance to this PFM");
  command
      .add_option("--integrator", options.integrator,
                  "whitted (diffuse light from the radiosity solution), twopass (direct light by shadow rays, "
                  "caustics from a photon map, the rest by a final gather over the solution), ppm (twopass with "
                  "progressive caustics) or path (reference)")
      ->check(CLI::IsMember({"whitted", "twopass", "ppm", "path"}))
      ->capture_default_str();
  command
      .add_option("--spp", options.spp,
                  "samples per pixel, stratified (1 = pixel centre). Default: whitted 16, which smooths edges and the "
                  "soft shadows of area lights; twopass and ppm 4 (with 16 shadow rays each and the cached gather, "
                  "about 2% from the reference in the Cornell box); path 256, which leaves about 8% noise per pixel "
                  "in the Cornell box")
      ->check(CLI::Range(1, 1 << 20));
  command
      .add_option("--adaptive-spp", options.adaptive_spp,
                  "trace pixels that differ from a neighbour again with this many samples, more than --spp (0: off)")
      ->check(CLI::Range(0, 1 << 20));
  command
      .add_option("--depth", options.depth,
                  "whitted, twopass, ppm: depth of the specular tree (default 8); path: longest path (default 1000)")
      ->check(CLI::Range(1, 100000));
  command
      .add_option("--light-samples", options.light_samples,
                  "whitted, twopass, ppm: shadow rays to area emitters per hit")
      ->check(CLI::Range(0, 1 << 16))
      ->capture_default_str();
  command
      .add_option("--direct", options.direct,
                  "Whitted two-pass: direct light by shadow rays (sharp) or from the radiosity solution")
      ->check(CLI::IsMember({"rays", "radiosity"}))
      ->capture_default_str();
  command.add_flag("--no-radiosity", options.no_radiosity,
                   "one-pass Whitted with a constant ambient term (solver options then set its coarse solution)");
  command
      .add_option("--ambient", options.ambient,
                  "with --no-radiosity: the ambient irradiance (default: mean indirect irradiance of a coarse "
                  "solution)")
      ->check(number_in(0.0, max_file_number));
  command.add_option("--seed", options.seed, "random seed: the picture depends on it alone")
      ->check(CLI::Validator(
          [](std::string& text) {
            return !text.empty() && text.find_first_not_of("0123456789") == std::string::npos
                       ? std::string()
                       : "'" + text + "' is not a whole number >= 0";
          },
          ">= 0"))
      ->capture_default_str();
  command
      .add_option("--photons", options.photons,
                  "twopass and ppm: caustic photons (ppm: per pass). Default: none if nothing in the scene is a "
                  "mirror or glass, else 500000 (twopass) or 200000 (ppm)")
      ->check(count_at_most(max_photons));
  command.add_option("--passes", options.passes, "ppm: photon passes, each with a smaller radius")
      ->check(CLI::Range(1, 1 << 16))
      ->capture_default_str();
  command
      .add_option("--gather-rays", options.gather_rays,
                  "twopass and ppm: final gather rays per irradiance record (stratified, cosine-weighted)")
      ->check(CLI::Range(1, 1 << 16))
      ->capture_default_str();
  command
      .add_option("--cache-accuracy", options.cache_accuracy,
                  "twopass and ppm: the irradiance cache's a (Ward 1988): smaller makes more records; 0 gathers at "
                  "every shading point")
      ->check(number_in(0.0, 10.0))
      ->capture_default_str();
  command.add_flag("--ray-baseline", options.ray_baseline,
                   "also cast the pixel-centre rays alone (closest hit, no shading) and compare rates");
  command.add_option("--exposure", options.exposure, "PNG value = radiance x exposure")
      ->check(number_in(min_exposure, max_exposure))
      ->capture_default_str();
  command.add_option("--stats", options.stats_path,
                     "write trace statistics (and the radiosity pass's) as JSON to this file");
}

namespace {

// Options the chosen integrator and passes would ignore (e.g. --ambient
// without --no-radiosity, solver options with the path tracer).
std::string check_integrator_options(const CLI::App& command, const trace_options& options) {
  auto given = [&](const char* name) { return command.count(name) > 0; };
  const bool path = options.integrator == "path";
  const bool gathered = options.integrator == "twopass" || options.integrator == "ppm";
  if (options.integrator != "ppm" && given("--passes")) return "--passes applies to --integrator ppm only";
  if (!gathered)
    for (const char* gather_only : {"--photons", "--gather-rays", "--cache-accuracy"})
      if (given(gather_only)) return std::string(gather_only) + " applies to --integrator twopass and ppm only";
  if (gathered)
    for (const char* whitted_only : {"--direct", "--no-radiosity", "--ambient"})
      if (given(whitted_only))
        return std::string(whitted_only) + " applies to --integrator whitted only (" + options.integrator +
               " takes direct light from shadow rays and needs the radiosity pass)";
  if (options.integrator == "ppm" && given("--adaptive-spp"))
    return "--adaptive-spp does not apply to --integrator ppm (its caustic points belong to the first samples)";
  if (path) {
    if (given("--light-samples")) return "--light-samples applies to --integrator whitted, twopass and ppm only";
    for (const char* whitted_only : {"--direct", "--no-radiosity", "--ambient"})
      if (given(whitted_only)) return std::string(whitted_only) + " applies to --integrator whitted only";
    if (std::string solver = given_options(command, solver_option_names()); !solver.empty())
      return solver +
             ": the path tracer makes no radiosity pass (solver options apply to --integrator whitted, twopass "
             "and ppm)";
  }
  if (given("--ambient") && !options.no_radiosity) return "--ambient applies with --no-radiosity only";
  if (options.no_radiosity && given("--direct"))
    return "--direct applies to two-pass stills only, not with --no-radiosity";
  if (options.no_radiosity && options.ambient)
    if (std::string solver = given_options(command, solver_option_names()); !solver.empty())
      return solver + ": with --no-radiosity and --ambient there is no radiosity pass";
  const int spp = options.spp > 0 ? options.spp : default_spp(options.integrator);
  if (options.adaptive_spp > 0 && options.adaptive_spp <= spp)
    return "--adaptive-spp " + std::to_string(options.adaptive_spp) + " must be more than --spp " +
           std::to_string(spp) + (options.spp > 0 ? "" : " (the default)") + " (0: off)";
  return {};
}

}  // namespace

std::string check_trace_options(const CLI::App& command, trace_options& options) {
  if (std::string e = check_solver_options(command, options.solver); !e.empty()) return e;
  if (std::string e = check_view_independent_option(command, options.solver); !e.empty()) return e;
  if (std::string e = check_integrator_options(command, options); !e.empty()) return e;
  if (std::string e = check_png_only(command, {"--exposure"}, options.out_path); !e.empty()) return e;
  return check_output_files(
      {{"--out", options.out_path, true}, {"--pfm", options.pfm_path, false}, {"--stats", options.stats_path, false}});
}

namespace {

// Solves `s` (the radiosity pass) and traces its camera's still.
int trace_scene(const scene& s, const trace_options& options) {
  solver_settings solver = options.solver;
  if (!options.view_independent) solver.view = s.view;  // the picture leads (hierarchical only)
  trace_params params;
  params.method = options.integrator == "path"      ? integrator::path
                  : options.integrator == "twopass" ? integrator::twopass
                  : options.integrator == "ppm"     ? integrator::ppm
                                                    : integrator::whitted;
  params.photons = options.photons;
  params.passes = options.passes;
  params.gather_rays = options.gather_rays;
  params.cache_accuracy = options.cache_accuracy;
  const bool gathered = params.method == integrator::twopass || params.method == integrator::ppm;
  params.spp = options.spp > 0 ? options.spp : default_spp(options.integrator);
  params.adaptive_spp = options.adaptive_spp;
  if (options.depth > 0) (params.method == integrator::path ? params.max_path : params.max_depth) = options.depth;
  params.light_samples = options.light_samples;
  params.seed = options.seed;
  params.diffuse = options.direct == "radiosity" ? diffuse_source::radiosity : diffuse_source::traced_direct;
  // The photon map (ppm keeps one pass's) and the picture, before anything
  // is traced: a count the memory could not hold, were every photon to
  // land in a caustic, is refused with its figures.
  const double photon_count = gathered && params.photons > 0 ? double(params.photons) : 0.0;
  const double still_bytes =
      photon_map_bytes(photon_count) + 3.0 * sizeof(float) * double(s.view.width) * s.view.height;
  char what[128];
  std::snprintf(what, sizeof what, "the still, were every photon to land in a caustic (%.0f photons, a %dx%d picture),",
                photon_count, s.view.width, s.view.height);
  if (!fits_in_memory(s, still_bytes, what, "use fewer --photons or a smaller --size")) return exit_input_error;

  // First pass: the radiosity solution, whose vertices the tracer's
  // diffuse term interpolates. One-pass stills take only a constant
  // ambient from a coarse solution (or the user).
  solved pass;
  std::unique_ptr<radiosity_field> field;
  if ((params.method == integrator::whitted && !options.no_radiosity) || gathered) {
    if (!solve(s, solver, pass)) return exit_input_error;
    const radiosity_solver& run = *pass.setup.solver;
    const solver_method method = method_of(run);
    say("radiosity: %zu elements, %llu %s, %s %.3f%%, %.3f s\n", solved_mesh(run).element_count(),
        static_cast<unsigned long long>(run.stats.steps), std::string(steps_word(method)).c_str(),
        std::string(remaining_word(method)).c_str(), 100.0 * run.stats.remaining, run.stats.seconds);
    field = std::make_unique<radiosity_field>(solved_mesh(run), pass.solution->radiosity, pass.solution->direct,
                                              pass.solution->ambient, pass.solution->caustic);
  } else if (params.method == integrator::whitted) {
    params.diffuse = diffuse_source::ambient;
    if (options.ambient) {
      params.ambient_irradiance = rgb(*options.ambient);
    } else {
      solver_settings coarse = solver;
      // Coarse, unless asked for: elements twice the solver's own default
      // (the hierarchical solver's default is already 2.4x the progressive one's).
      if (coarse.max_edge <= 0.0) coarse.max_edge = 2.0 * mesher_params_for(solver, s).max_edge;
      if (!solve(s, coarse, pass)) return exit_input_error;
      params.ambient_irradiance = mean_indirect_irradiance(solved_mesh(*pass.setup.solver), *pass.solution);
    }
    say("one pass: ambient irradiance %.4g %.4g %.4g\n", params.ambient_irradiance.r, params.ambient_irradiance.g,
        params.ambient_irradiance.b);
  }

  const auto build_start = clock_type::now();
  const ray_scene rays(s);
  const double build_seconds = std::chrono::duration<double>(clock_type::now() - build_start).count();

  trace_progress progress;
  trace_stats stats;
  auto job = std::async(std::launch::async,
                        [&] { return trace_image(s, s.view, rays, field.get(), params, &progress, &stats); });
  {
    // One line per stage: photons, the cache's records, the pixels, ppm's
    // photon passes.
    std::unique_ptr<progress_line> line;
    trace_stage shown = trace_stage::pixels;
    while (job.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
      const trace_stage stage = progress.stage;
      if (!line || stage != shown) {
        line.reset();
        const char* what = stage == trace_stage::photons  ? "photons"
                           : stage == trace_stage::cache  ? "gathering"
                           : stage == trace_stage::passes ? "photon passes"
                                                          : "tracing";
        line = std::make_unique<progress_line>(what);
        shown = stage;
      }
      auto fraction = [](long done, long total) { return total > 0 ? double(done) / double(total) : 0.0; };
      if (stage == trace_stage::photons)
        line->update(fraction(progress.photons.photons_done, progress.photons.photons_total),
                     std::to_string(progress.photons.photons_total.load()) + " photons");
      else if (stage == trace_stage::cache)
        line->update(fraction(progress.cache_points_done, progress.cache_points_total), "irradiance cache");
      else if (stage == trace_stage::passes)
        line->update(fraction(progress.passes_done, progress.passes_total),
                     "pass " + std::to_string(progress.passes_done.load()) + " of " +
                         std::to_string(progress.passes_total.load()));
      else
        line->update(fraction(progress.pixels_done, progress.pixels_total), std::to_string(params.spp) + " spp");
    }
  }
  const image img = job.get();
  if (gathered)
    say("%s: %llu photons (%llu stored) in %.3f s%s; irradiance cache %llu records (%llu points gathered on the spot), "
        "%llu gather rays, %.3f s\n",
        options.integrator.c_str(), static_cast<unsigned long long>(stats.photons_emitted),
        static_cast<unsigned long long>(stats.photons_stored), stats.photon_seconds,
        params.method == integrator::ppm
            ? (", " + std::to_string(stats.passes) + " passes, final radius " + std::to_string(stats.final_radius))
                  .c_str()
            : "",
        static_cast<unsigned long long>(stats.cache_records), static_cast<unsigned long long>(stats.cache_misses),
        static_cast<unsigned long long>(stats.gather_rays), stats.cache_seconds);

  const double rays_total = double(stats.primary_rays + stats.shadow_rays + stats.secondary_rays);
  say("traced %dx%d (%s, %d spp%s) in %.3f s (scene build %.3f s): %llu primary, %llu shadow, %llu secondary rays, "
      "%.2f Mrays/s\n",
      img.width, img.height, options.integrator.c_str(), params.spp,
      options.adaptive_spp ? (", " + std::to_string(stats.refined_pixels) + " pixels refined").c_str() : "",
      stats.seconds, build_seconds, static_cast<unsigned long long>(stats.primary_rays),
      static_cast<unsigned long long>(stats.shadow_rays), static_cast<unsigned long long>(stats.secondary_rays),
      stats.seconds > 0 ? rays_total / stats.seconds * 1e-6 : 0.0);

  if (options.ray_baseline) {
    // The same scene's closest-hit query alone, on all cores, 10 passes over
    // the pixel-centre rays: what the tracer's rate is measured against.
    const int w = s.view.width, h = s.view.height, passes = 10;
    std::atomic<std::size_t> hits{0};
    const auto start = clock_type::now();
    tbb::parallel_for(tbb::blocked_range<int>(0, h * passes), [&](const tbb::blocked_range<int>& r) {
      std::size_t local = 0;
      for (int row = r.begin(); row < r.end(); ++row)
        for (int x = 0; x < w; ++x)
          local += rays.intersect(s.view.eye, camera_ray_direction(s.view, x + 0.5, row % h + 0.5)).has_value();
      hits += local;
    });
    const double seconds = std::chrono::duration<double>(clock_type::now() - start).count();
    const double raw = double(w) * h * passes / seconds * 1e-6;
    const double traced = stats.seconds > 0 ? rays_total / stats.seconds * 1e-6 : 0.0;
    say("ray baseline: closest hits alone %.2f Mrays/s (%zu hits); the tracer's %.2f Mrays/s, shading included, "
        "is %.0f%% of it\n",
        raw, hits.load(), traced, raw > 0 ? 100.0 * traced / raw : 0.0);
  }

  std::string error;
  if (!options.stats_path.empty()) {
    nlohmann::json out = {{"trace",
                           {{"integrator", options.integrator},
                            {"width", img.width},
                            {"height", img.height},
                            {"spp", params.spp},
                            {"primary_rays", stats.primary_rays},
                            {"shadow_rays", stats.shadow_rays},
                            {"secondary_rays", stats.secondary_rays},
                            {"refined_pixels", stats.refined_pixels},
                            {"seconds", stats.seconds},
                            {"scene_build_seconds", build_seconds}}}};
    if (gathered) {
      out["trace"]["photons"] = {
          {"emitted", stats.photons_emitted}, {"stored", stats.photons_stored}, {"seconds", stats.photon_seconds}};
      if (params.method == integrator::ppm) {
        out["trace"]["photons"]["passes"] = stats.passes;
        out["trace"]["photons"]["final_radius"] = stats.final_radius;
      }
      out["trace"]["irradiance_cache"] = {{"records", stats.cache_records},
                                          {"misses", stats.cache_misses},
                                          {"gather_rays", stats.gather_rays},
                                          {"seconds", stats.cache_seconds}};
    }
    // The radiosity pass, when the still used one (two-pass, or the coarse
    // solution a one-pass ambient term came from).
    if (pass.setup.solver)
      out["radiosity"] =
          solver_stats_json(s, pass.settings, *pass.setup.mesh, *pass.setup.solver, pass.setup.mesh_seconds);
    if (!write_stats(options.stats_path, out, error)) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return exit_input_error;
    }
  }
  if (!write_picture(options.out_path, img, options.exposure, error)) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return exit_input_error;
  }
  const std::optional<picture_format> format = picture_format_of(options.out_path);
  say("wrote %s (%dx%d%s)\n", std::filesystem::absolute(options.out_path).string().c_str(), img.width, img.height,
      format && is_linear(*format) ? ", linear radiance" : "");
  if (!options.pfm_path.empty()) {
    if (!write_pfm(options.pfm_path, img, error)) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return exit_input_error;
    }
    say("wrote %s (linear radiance)\n", options.pfm_path.c_str());
  }
  return exit_ok;
}

}  // namespace

int run_trace(const trace_options& options) {
  const setup_time_limit limit(options.solver.stop.seconds);  // loading and meshing count
  scene s;
  if (int code =
          load_for_command(options.scene, &options.camera, s, nullptr,
                           {{"--out", options.out_path}, {"--pfm", options.pfm_path}, {"--stats", options.stats_path}});
      code != exit_ok)
    return code;
  return trace_scene(s, options);
}

}  // namespace bounce
