#include "render_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "console.h"
#include "image/picture_file.h"
#include "mesh/patch_mesh.h"
#include "offscreen_view.h"
#include "panel.h"
#include "radiosity/radiosity.h"
#include "scene/camera_math.h"
#include "scene/framing.h"
#include "solver_stats.h"

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

int run_render(const scene& s, const solver_settings& solver, const render_options& options) {
  patch_mesh mesh;
  std::string error;
  const auto mesh_start = std::chrono::steady_clock::now();
  if (!make_patch_mesh(s, mesher_params_for(solver, s), mesh, error)) {
    std::fprintf(stderr, "error: %s: %s\n", s.source.c_str(), error.c_str());
    return exit_input_error;
  }
  const double mesh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - mesh_start).count();
  warn_about_mesh(s, mesh);
  headless::offscreen_view view(s.view.width, s.view.height, options.msaa);
  if (!view.ok()) {
    std::fprintf(stderr, "error: %s\n", view.error().c_str());
    return exit_input_error;
  }
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
  settings.colours = options.colours == "unshot" ? gl::false_colour::unshot
                     : options.colours == "size" ? gl::false_colour::element_size
                                                 : gl::false_colour::none;

  // The panel, headless: ImGui needs no platform backend, only a display
  // size and a few frames to lay its windows out.
  std::unique_ptr<radiosity_state> state;
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
    io.DisplaySize = ImVec2(float(s.view.width), float(s.view.height));
    io.DeltaTime = 1.0f / 60.0f;
    ImGui_ImplOpenGL3_Init("#version 330 core");
    imgui.active = true;
    overlay = [&] {
      worker_view v;
      v.source = std::shared_ptr<const scene>(&s, [](const scene*) {});
      v.mesh = state->refined_mesh ? state->refined_mesh
                                   : std::shared_ptr<const patch_mesh>(&mesh, [](const patch_mesh*) {});
      v.solution = make_snapshot(*state);
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
    if (!write_png(path, s.view.width, s.view.height, 3, rgb.data(), error)) {
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
  state = make_radiosity_state(s, mesh, radiosity_params_for(solver));
  // The solution on screen; adaptive meshing brings a refined mesh to upload first.
  const patch_mesh* shown_mesh = &mesh;
  auto show = [&](const radiosity_state& st) {
    if (st.mesh != shown_mesh) {
      view.renderer().upload(*st.mesh, source);
      shown_mesh = st.mesh;
    }
    view.renderer().update(*make_snapshot(st));
  };
  bool frames_ok = true;
  std::size_t frames = 0;
  std::uint64_t next_frame = 1, last_frame_step = ~std::uint64_t(0);
  auto write_numbered_frame = [&](const radiosity_state& st) {
    show(st);
    char name[64];
    // Named by step (shots and refinement passes), so that no frame overwrites another.
    last_frame_step = st.stats.shots + st.stats.refinements;
    std::snprintf(name, sizeof name, "frame_%06llu.png", static_cast<unsigned long long>(last_frame_step));
    frames_ok = write_frame((std::filesystem::path(options.frames_dir) / name).string());
    ++frames;
  };
  progress_line progress("solving");
  run_radiosity(*state, solver.stop, [&](const radiosity_state& st) {
    progress.update(
        solve_progress(st.stats.unshot_fraction, solver.stop.unshot_fraction, st.stats.seconds, solver.stop.seconds),
        unshot_text(st.stats.unshot_fraction));
    if (options.panel) history.push_back({st.stats.seconds, st.stats.unshot_fraction});
    if (options.frames_dir.empty() || !frames_ok || st.stats.shots == 0) return;
    // A fixed spacing, or doubling counts: the early shots change the picture most.
    const bool due = options.frame_every > 0 ? st.stats.shots % std::uint64_t(options.frame_every) == 0
                                             : st.stats.shots >= next_frame;
    if (!due) return;
    while (next_frame <= st.stats.shots) next_frame *= 2;
    write_numbered_frame(st);
  });
  progress.done();
  if (frames_ok && !options.frames_dir.empty() && last_frame_step != state->stats.shots + state->stats.refinements)
    write_numbered_frame(*state);  // and the converged picture
  if (!frames_ok) return exit_input_error;

  show(*state);
  const std::optional<picture_format> format = picture_format_of(options.out_path);
  if (format && is_linear(*format)) {
    if (!write_picture(options.out_path, view.render_linear(view_projection, eye, settings), 1.0, error)) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return exit_input_error;
    }
  } else if (!write_frame(options.out_path)) {
    return exit_input_error;
  }
  say("solved: %llu shots, unshot %.4f%%, %zu elements, %.3f s\n", static_cast<unsigned long long>(state->stats.shots),
      100.0 * state->stats.unshot_fraction, state->mesh->element_count(), state->stats.seconds);
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
    if (!write_stats(options.stats_path, solver_stats_json(s, solver, mesh, *state, mesh_seconds), error)) {
      std::fprintf(stderr, "error: %s\n", error.c_str());
      return exit_input_error;
    }
    say("wrote %s (statistics)\n", options.stats_path.c_str());
  }
  return exit_ok;
}

}  // namespace bounce
