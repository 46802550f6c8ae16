#include "cli/render_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <CLI/CLI.hpp>

#include "cli/console.h"
#include "cli/option_values.h"
#include "cli/scene_argument.h"
#include "cli/solver_options.h"
#include "cli/solver_stats.h"
#include "cli/time_limit.h"
#include "common/exit_code.h"
#include "headless/offscreen_view.h"
#include "image/picture_file.h"
#include "mesh/patch_mesh.h"
#include "radiosity/solve.h"
#include "scene/camera_math.h"
#include "scene/framing.h"
#include "viewer/panel.h"

namespace bounce {
namespace {

// RGBA rows to RGB rows (PNG output has no alpha).
std::vector<unsigned char> drop_alpha(const std::vector<unsigned char>& rgba) {
  std::vector<unsigned char> rgb;
  rgb.reserve(rgba.size() / 4 * 3);
  for (std::size_t i = 0; i < rgba.size(); i += 4)
    rgb.insert(rgb.end(), rgba.begin() + std::ptrdiff_t(i), rgba.begin() + std::ptrdiff_t(i + 3));
  return rgb;
}

}  // namespace

void add_render_options(CLI::App& command, render_options& options) {
  add_scene_argument(command, options.scene);
  add_solver_options(command, options.solver);
  add_view_independent_option(command, options.view_independent);
  add_camera_options(command, options.camera);
  command
      .add_option("--out", options.out_path,
                  "picture of the Gouraud view; the extension picks the format: .png (tone-mapped), or .pfm, .exr, "
                  ".hdr (linear radiance, unscaled)")
      ->capture_default_str();
  command.add_option("--pfm", options.pfm_path, "also write the view in linear radiance to this PFM");
  CLI::Option* frames = command.add_option(
      "--frames", options.frames_dir,
      "also write PNG frames of the convergence into DIR: after 1, 2, 4, 8, ... steps and at the end");
  command
      .add_option("--frame-every", options.frame_every,
                  "with --frames: a frame every N steps instead of at doubling counts")
      ->check(CLI::Range(1L, 1L << 40))
      ->needs(frames);
  command.add_option("--exposure", options.exposure, "displayed value = radiance x exposure")
      ->check(number_in(min_exposure, max_exposure))
      ->capture_default_str();
  command.add_option("--tone", options.curve, "tone curve")
      ->check(CLI::IsMember({"srgb", "filmic"}))
      ->capture_default_str();
  command.add_flag("--wireframe", options.wireframe, "draw element edges");
  command.add_option("--stats", options.stats_path, "write solver statistics as JSON to this file");
  command.add_flag("--ambient", options.ambient,
                   "add the ambient term of the power still to go (unshot, or the residual; display only)");
  command.add_flag("--panel", options.panel,
                   "draw the ImGui panel beside the view, as in the window (the PNG is wider)");
  command
      .add_option("--colours", options.colours,
                  "radiance, or false colour of the remaining power (unshot, or the residual) or element size")
      ->check(CLI::IsMember({"radiance", "remaining", "size"}))
      ->capture_default_str();
  command
      .add_option("--msaa", options.msaa, "antialiasing samples per pixel; 0 draws as the window does on software GL")
      ->check(CLI::IsMember({0, 1, 2, 4, 8}))
      ->capture_default_str();
}

std::string check_render_options(const CLI::App& command, render_options& options) {
  if (std::string e = check_solver_options(command, options.solver); !e.empty()) return e;
  if (std::string e = check_view_independent_option(command, options.solver); !e.empty()) return e;
  if (std::string e = check_png_only(command, {"--panel", "--tone", "--exposure"}, options.out_path); !e.empty())
    return e;
  if (!options.frames_dir.empty()) {
    namespace fs = std::filesystem;
    const fs::path parent = fs::absolute(options.frames_dir).parent_path();
    std::error_code ec;
    if (!fs::is_directory(options.frames_dir, ec) && !fs::is_directory(parent, ec))
      return "--frames " + options.frames_dir + ": the folder " + parent.string() + " does not exist";
  }
  return check_output_files(
      {{"--out", options.out_path, true}, {"--pfm", options.pfm_path, false}, {"--stats", options.stats_path, false}});
}

int run_render(const render_options& options) {
  const setup_time_limit limit(options.solver.stop.seconds);  // loading and meshing count
  scene s;
  if (int code =
          load_for_command(options.scene, &options.camera, s, nullptr,
                           {{"--out", options.out_path}, {"--pfm", options.pfm_path}, {"--stats", options.stats_path}});
      code != exit_ok)
    return code;
  return render_scene(s, options);
}

int render_scene(const scene& s, const render_options& options) {
  // The picture: colour and depth per sample, and the linear read-back.
  const double pixels = double(s.view.width) * double(s.view.height);
  const double picture_bytes = pixels * (8.0 * std::max(1, options.msaa) + 3.0 * sizeof(float));
  char what[96];
  std::snprintf(what, sizeof what, "the %dx%d picture at %d samples", s.view.width, s.view.height,
                std::max(1, options.msaa));
  if (!fits_in_memory(s, picture_bytes, what, "use a smaller --size or --msaa")) return exit_input_error;
  solver_settings solver = options.solver;
  if (!options.view_independent) solver.view = s.view;  // the picture leads (hierarchical only)
  solve_setup setup;
  if (!start_command_solve(s, solver, setup)) return exit_input_error;
  std::string error;
  const patch_mesh& mesh = *setup.mesh;
  radiosity_solver& run = *setup.solver;
  warn_about_mesh(s, mesh);
  // --panel: the panel docked beside the picture, as in the window.
  const int panel_width = options.panel ? int(std::lround(docked_width(panel_layout{}, 1e9f))) : 0;
  const int picture_width = s.view.width + panel_width;
  headless::offscreen_view view(picture_width, s.view.height, options.msaa);
  view.set_view_width(s.view.width);
  if (!view.ok()) {
    std::fprintf(stderr, "error: %s\n", view.error().c_str());
    return exit_input_error;
  }
  if (options.msaa > 1 && view.samples() < options.msaa)
    std::fprintf(stderr, "warning: --msaa %d: this GL draws at most %d samples per pixel; drawn with %d\n",
                 options.msaa, view.samples(), view.samples());
  // The renderer takes the scene for its textures and background; `s` outlives it.
  const std::shared_ptr<const scene> source(&s, [](const scene*) {});
  view.renderer().upload(mesh, source);
  const glm::mat4 view_projection(projection_matrix(s.view, scene_bounds(s)) * view_matrix(s.view));
  const glm::vec3 eye(s.view.eye);
  gl::display_settings settings;
  settings.exposure = options.exposure;
  settings.curve = options.curve == "filmic" ? gl::tone_curve::filmic : gl::tone_curve::srgb;
  settings.wireframe = options.wireframe;
  settings.ambient = options.ambient;
  settings.colours = options.colours == "remaining" ? gl::false_colour::remaining
                     : options.colours == "size"    ? gl::false_colour::element_size
                                                    : gl::false_colour::none;

  // The panel, headless: ImGui needs no platform backend, only a display
  // size and a few frames to lay its windows out.
  convergence_log history;
  struct imgui_scope {
    bool active = false;
    ~imgui_scope() {
      if (!active) return;
      ImGui_ImplOpenGL3_Shutdown();
      ImGui::DestroyContext();
    }
  } imgui;
  std::function<void()> overlay;
  if (options.panel) {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(float(picture_width), float(s.view.height));
    io.DeltaTime = 1.0f / 60.0f;
    ImGui_ImplOpenGL3_Init("#version 330 core");
    imgui.active = true;
    overlay = [&] {
      worker_view v;
      v.source = std::shared_ptr<const scene>(&s, [](const scene*) {});
      v.mesh = refined_mesh(run) ? refined_mesh(run) : setup.mesh;
      v.solution = make_snapshot(run);
      v.history = history;
      v.converged = true;
      v.settings = solver;
      v.meshed_elements = mesh.element_count();
      panel_state panel;
      panel.scene_path = s.source;
      panel.solver = solver;
      panel.display = settings;
      for (int frame = 0; frame < 3; ++frame) {
        ImGui_ImplOpenGL3_NewFrame();
        ImGui::NewFrame();
        draw_panel(panel, v, 0.0);
        ImGui::Render();
      }
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    };
  }

  auto write_frame = [&](const std::string& path) -> bool {
    const std::vector<unsigned char> rgb = drop_alpha(view.render_rgba8(view_projection, eye, settings, overlay));
    if (!write_png(path, picture_width, s.view.height, 3, rgb.data(), error)) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return false;
    }
    return true;
  };

  if (!options.frames_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(options.frames_dir, ec);
    if (ec) {
      std::fprintf(stderr, "error: %s: cannot create the frames folder: %s\n", options.frames_dir.c_str(),
                   ec.message().c_str());
      return exit_input_error;
    }
  }
  // The solution on screen; a refined mesh is uploaded first.
  const patch_mesh* shown_mesh = &mesh;
  auto show = [&](const radiosity_solver& st) {
    if (&solved_mesh(st) != shown_mesh) {
      shown_mesh = &solved_mesh(st);
      view.renderer().upload(*shown_mesh, source);
    }
    view.renderer().update(*make_snapshot(st));
  };
  bool frames_ok = true;
  std::size_t frames = 0;
  std::uint64_t next_frame = 1, last_frame_step = ~std::uint64_t(0);
  auto write_numbered_frame = [&](const radiosity_solver& st) {
    show(st);
    char name[64];
    // Named by steps and refinement passes, so that no frame overwrites another.
    last_frame_step = st.stats.steps + st.stats.refinements;
    std::snprintf(name, sizeof name, "frame_%06llu.png", static_cast<unsigned long long>(last_frame_step));
    frames_ok = write_frame((std::filesystem::path(options.frames_dir) / name).string());
    ++frames;
  };
  progress_line progress("solving");
  const solver_method method = method_of(run);
  const stop_criterion stop = with_time_left(solver.stop);
  run_solver(run, stop, [&](const radiosity_solver& st) {
    progress.update(solve_progress(st.stats.remaining, stop.remaining, st.stats.seconds, stop.seconds),
                    remaining_text(method, st.stats.remaining));
    if (options.panel) history.push_back({st.stats.seconds, st.stats.remaining, st.stats.refinements});
    if (options.frames_dir.empty() || !frames_ok || st.stats.steps == 0) return;
    // A fixed spacing, or doubling counts: the early steps change the picture most.
    const bool due = options.frame_every > 0 ? st.stats.steps % std::uint64_t(options.frame_every) == 0
                                             : st.stats.steps >= next_frame;
    if (!due) return;
    while (next_frame <= st.stats.steps) next_frame *= 2;
    write_numbered_frame(st);
  });
  progress.done();
  warn_about_solve(s, run);
  if (frames_ok && !options.frames_dir.empty() && last_frame_step != run.stats.steps + run.stats.refinements)
    write_numbered_frame(run);  // and the converged picture
  if (!frames_ok) return exit_input_error;

  show(run);
  const std::optional<picture_format> format = picture_format_of(options.out_path);
  if (format && is_linear(*format)) {
    if (!write_picture(options.out_path, view.render_linear(view_projection, eye, settings), 1.0, error)) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return exit_input_error;
    }
  } else if (!write_frame(options.out_path)) {
    return exit_input_error;
  }
  say("solved: %llu %s, %s %.4f%%, %zu elements, %.3f s\n", static_cast<unsigned long long>(run.stats.steps),
      std::string(steps_word(method)).c_str(), std::string(remaining_word(method)).c_str(), 100.0 * run.stats.remaining,
      solved_mesh(run).element_count(), run.stats.seconds);
  say("wrote %s (%dx%d%s)\n", std::filesystem::absolute(options.out_path).string().c_str(), s.view.width, s.view.height,
      format && is_linear(*format) ? ", linear radiance" : "");
  if (!options.pfm_path.empty()) {
    if (!write_pfm(options.pfm_path, view.render_linear(view_projection, eye, settings), error)) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return exit_input_error;
    }
    say("wrote %s (linear radiance)\n", options.pfm_path.c_str());
  }
  if (frames) say("wrote %zu frames to %s\n", frames, options.frames_dir.c_str());
  if (!options.stats_path.empty()) {
    if (!write_stats(options.stats_path, solver_stats_json(s, solver, mesh, run, setup.mesh_seconds), error)) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return exit_input_error;
    }
    say("wrote %s (statistics)\n", options.stats_path.c_str());
  }
  return exit_ok;
}

}  // namespace bounce
