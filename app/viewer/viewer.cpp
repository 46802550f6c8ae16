#include "viewer/viewer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

#include <glad/gl.h>
// glad first: GLFW must not pull in a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "base/whole_file.h"
#include "common/exit_code.h"
#include "image/image.h"
#include "render/mesh_renderer.h"
#include "scene/camera_file.h"
#include "scene/camera_math.h"
#include "scene/framing.h"
#include "scene/orbit.h"
#include "scene/scene_io.h"
#include "scene/warning_groups.h"
#include "trace/back_faces.h"
#include "trace/ray_scene.h"
#include "viewer/bake_action.h"
#include "viewer/error_tracker.h"
#include "viewer/exposure_control.h"
#include "viewer/input.h"
#include "viewer/panel.h"
#include "viewer/picture_quad.h"
#include "viewer/rest_refiner.h"
#include "viewer/scripted_run.h"
#include "viewer/solver_worker.h"
#include "viewer/still_job.h"
#include "viewer/user_files.h"
#include "viewer/window.h"

namespace bounce {
namespace {

using clock_type = std::chrono::steady_clock;

const char* const tracing_message = "tracing a still...";

// How long the camera must rest before the view refines towards the still.
constexpr double rest_seconds = 0.4;

// The headlit preview's radiance times the exposure: a white surface facing
// the eye shows at 0.6 before the tone curve.
constexpr double preview_radiance = 0.6;

bool same_view(const orbit_state& a, const orbit_state& b) {
  return a.target == b.target && a.distance == b.distance && a.yaw == b.yaw && a.pitch == b.pitch;
}

double milliseconds_since(clock_type::time_point start) {
  return 1000.0 * std::chrono::duration<double>(clock_type::now() - start).count();
}

trace_params still_params(const still_settings& settings) {
  trace_params p;
  constexpr integrator in_panel_order[] = {integrator::whitted, integrator::twopass, integrator::ppm, integrator::path};
  p.method = in_panel_order[std::clamp(settings.integrator, 0, 3)];
  p.spp = std::max(1, settings.spp);
  p.diffuse = settings.direct == 1 ? diffuse_source::radiosity : diffuse_source::traced_direct;
  return p;
}

// What the panel and the keys asked for, together.
panel_actions either(panel_actions a, const panel_actions& b) {
  a.open_scene |= b.open_scene;
  a.apply_mesh |= b.apply_mesh;
  a.pause |= b.pause;
  a.resume |= b.resume;
  a.step |= b.step;
  a.restart |= b.restart;
  a.screenshot |= b.screenshot;
  a.bake |= b.bake;
  a.frame_scene |= b.frame_scene;
  a.reset_camera |= b.reset_camera;
  a.trace_still |= b.trace_still;
  a.cancel_still |= b.cancel_still;
  a.save_still_png |= b.save_still_png;
  a.save_still_pfm |= b.save_still_pfm;
  a.compute_reference |= b.compute_reference;
  a.cancel_reference |= b.cancel_reference;
  a.set_stop |= b.set_stop;
  a.set_view |= b.set_view;
  a.quit |= b.quit;
  a.save_camera |= b.save_camera;
  a.save_layout |= b.save_layout;
  a.add_bookmark |= b.add_bookmark;
  if (b.go_to_bookmark >= 0) a.go_to_bookmark = b.go_to_bookmark;
  if (b.delete_bookmark >= 0) a.delete_bookmark = b.delete_bookmark;
  return a;
}

// The window between frames: the solver's published work as uploaded, the
// camera, the panel, the still and the error plot. GL calls stay here, on
// the UI thread; the solver, the still and the error plot run on their own.
class viewer_app {
 public:
  viewer_app(GLFWwindow* window, window_input& input, const scene& initial, const solver_settings& solver,
             const viewer_options& options);
  ~viewer_app();
  viewer_app(const viewer_app&) = delete;
  viewer_app& operator=(const viewer_app&) = delete;

  // The frame loop, until the window closes; returns the exit code.
  int run();
  // Whether work is under way that closing would wait for: a solver step,
  // a still, a reference, a scene check.
  bool working() const { return !worker_.idle() || still_.running() || errors_.status("").computing || checks_.busy(); }

 private:
  void take_published_work(const worker_view& view);
  void take_still(int frame);
  // Draws the view and the panel; saves a screenshot before or after the
  // panel as asked. Returns the panel's actions.
  panel_actions draw(const worker_view& view, int frame, panel_actions& keys);
  void carry_out(const panel_actions& act, const worker_view& view);
  // Refinement at rest: starts it when the camera has rested, drops it when
  // anything the picture depends on changes, uploads new passes.
  void refine_at_rest(const worker_view& view);
  // Importance from the window's camera: once the camera has rested, the
  // solver's refinement is re-targeted at what the window shows.
  void lead_solver(const worker_view& view);
  // The shown scene's bounds, found once per scene: a scan of every
  // vertex, too slow to repeat every frame on a large scene.
  const bounds3& bounds(const worker_view& view) {
    if (!bounds_found_ || view.source != bounds_source_) {
      bounds_ = view.source ? scene_bounds(*view.source) : scene_bounds(initial_);
      bounds_source_ = view.source;
      bounds_found_ = true;
    }
    return bounds_;
  }

  GLFWwindow* window_;
  window_input& input_;
  const scene& initial_;
  const viewer_options& options_;
  int code_ = exit_ok;

  gl::mesh_renderer renderer_;
  solver_worker worker_;
  panel_state panel_;
  camera scene_camera_;
  orbit_state orbit_;
  pointer_state pointer_;
  std::shared_ptr<const patch_mesh> uploaded_mesh_;
  std::shared_ptr<const scene> shown_source_;
  std::shared_ptr<const scene> bounds_source_;
  bounds3 bounds_;
  bool bounds_found_ = false;
  std::shared_ptr<const radiosity_snapshot> uploaded_solution_;  // a snapshot is new when it is another object
  std::string shown_error_;
  double frame_ms_ = 0.0;
  int width_ = 0, height_ = 0;  // the view's part of the framebuffer (left of the panel), this frame
  int framebuffer_width_ = 0;   // the whole framebuffer, panel included

  still_job still_;  // the ray-traced still, traced on its own thread, shown as a texture
  still_status still_shown_;
  std::uint64_t still_uploaded_ = 0;
  double still_exposure_ = 0.0;

  rest_refiner refiner_;              // passes of the still's integrator while the camera rests
  picture_quad refined_;              // their blend with the live view, drawn over the Gouraud view
  std::optional<camera> rest_start_;  // passes to start once the live view is drawn
  int refined_passes_ = 0;
  double refined_exposure_ = 0.0;
  orbit_state rested_orbit_;
  int rested_width_ = 0, rested_height_ = 0;
  std::shared_ptr<const radiosity_snapshot> refined_solution_;  // what the passes trace with
  std::shared_ptr<const scene> refined_source_;
  // The camera the solver was last led by (its orbit and aspect), per scene.
  std::shared_ptr<const scene> led_source_;
  orbit_state led_orbit_;
  int led_width_ = 0, led_height_ = 0;
  clock_type::time_point last_motion_ = clock_type::now();

  bool pause_asked_ = false;   // Pause sent, the worker still ending its step
  exposure_control exposure_;  // automatic exposure, when the panel has it on
  error_tracker errors_;       // error against time: a path-traced reference of the camera on request
  bool reference_requested_ = false;

  scripted_run script_;
  frame_timing timing_;
  clock_type::time_point started_ = clock_type::now();

  // The share of the scene camera's view that is back faces, checked off
  // the UI thread for each scene opened (-1: not known yet).
  std::atomic<double> back_faces_{-1.0};
  // The shown scene for rays, built off the UI thread with that check: the
  // orbit turns about the point under the cursor and stays out of walls.
  struct scene_rays {
    explicit scene_rays(std::shared_ptr<const scene> s) : source(std::move(s)), rays(*source) {}
    std::shared_ptr<const scene> source;  // the rays refer to it
    ray_scene rays;
  };
  std::shared_ptr<const scene_rays> picking_;  // atomic_load / atomic_store: the checks' thread writes it
  background_worker checks_;                   // last: destroyed first, so no check outlives what it writes
};

viewer_app::viewer_app(GLFWwindow* window, window_input& input, const scene& initial, const solver_settings& solver,
                       const viewer_options& options)
    : window_(window),
      input_(input),
      initial_(initial),
      options_(options),
      scene_camera_(initial.view),
      orbit_(orbit_from_camera(initial.view)),
      script_(options) {
  std::string error;
  if (!renderer_.init(error) || !refined_.init(error)) {
    std::fprintf(stderr, "error: %s", error.c_str());
    code_ = exit_input_error;
  }
  worker_.load(initial, solver, options.load_warnings);
  if (options.start_paused) worker_.pause();
  panel_.layout = read_panel_layout();
  if (options.exposure > 0.0) {
    panel_.display.exposure = options.exposure;
    panel_.auto_exposure = false;
  }
  panel_.scene_path = initial.source;
  panel_.solver = solver;
  panel_.refine_at_rest = options.refine_at_rest;
  panel_.asset_scenes = find_asset_scenes();
  panel_.recent_scenes = read_recent_scenes();
  glfwSetWindowTitle(window, window_title(initial.source).c_str());
  if (!options.still_path.empty()) {  // a scripted still has the scene camera's --size
    panel_.still.window_size = false;
    panel_.still.size[0] = initial.view.width;
    panel_.still.size[1] = initial.view.height;
  }
  glfwGetCursorPos(window, &pointer_.x, &pointer_.y);
}

viewer_app::~viewer_app() {
  if (still_shown_.texture) glDeleteTextures(1, &still_shown_.texture);
}

// A new mesh is uploaded once (a new scene, density or refinement pass),
// then only the radiosity buffer changes.
void viewer_app::take_published_work(const worker_view& view) {
  if (view.mesh && view.mesh != uploaded_mesh_) {
    const auto start = clock_type::now();
    if (view.mesh_arrays)
      renderer_.upload(*view.mesh_arrays);
    else
      renderer_.upload(*view.mesh, view.source);
    glFinish();
    timing_.mesh_upload(milliseconds_since(start));
    uploaded_mesh_ = view.mesh;
    uploaded_solution_.reset();
  }
  if (view.source != shown_source_) {
    const bool opened_in_window = shown_source_ != nullptr;
    if (shown_source_) {  // a newly opened scene brings its camera, and the old still goes
      scene_camera_ = view.source->view;
      orbit_ = orbit_from_camera(scene_camera_);
      still_.cancel();
      if (still_shown_.texture) glDeleteTextures(1, &still_shown_.texture);
      still_shown_ = {};
      panel_.show_still = false;
    }
    shown_source_ = view.source;
    exposure_.start();  // a new scene: its own exposure at once
    if (view.source) {
      back_faces_ = -1.0;
      std::atomic_store(&picking_, std::shared_ptr<const scene_rays>());
      checks_.post([this, source = view.source] {
        auto rays = std::make_shared<const scene_rays>(source);
        back_faces_ = back_face_fraction(*source, source->view, rays->rays);
        std::atomic_store(&picking_, std::shared_ptr<const scene_rays>(std::move(rays)));
      });
      glfwSetWindowTitle(window_, window_title(view.source->source).c_str());
      // A scene opened in the window says its warnings on the terminal too,
      // grouped as the command line does (the first scene's were said there).
      if (opened_in_window && view.warnings)
        for (const warning_group& g : group_warnings(*view.warnings))
          std::fprintf(stderr, "warning: %s\n", describe(g).c_str());
      panel_.recent_scenes = remember_scene(view.source->source);
      panel_.bookmarks = read_bookmarks(view.source->source);
    }
  }
  if (view.solution && view.solution != uploaded_solution_) {
    const auto start = clock_type::now();
    if (view.colours)
      renderer_.update(*view.colours, glm::vec3(view.solution->ambient));
    else
      renderer_.update(*view.solution);
    glFinish();  // llvmpipe copies on the CPU: finish so the time is the upload's
    timing_.upload(milliseconds_since(start));
    uploaded_solution_ = view.solution;
  }
  if (view.error != shown_error_) {
    shown_error_ = view.error;
    if (!shown_error_.empty()) std::fprintf(stderr, "error: %s\n", shown_error_.c_str());
  }
}

void viewer_app::take_still(int frame) {
  if (const auto result = still_.result();
      result && result->source == shown_source_ &&
      (result->version != still_uploaded_ || panel_.display.exposure != still_exposure_)) {
    if (result->version != still_uploaded_) {  // a new still: show it, and say it is done
      panel_.show_still = true;
      if (panel_.message == tracing_message) panel_.message.clear();
    }
    upload_srgb_texture(still_shown_.texture, result->picture, panel_.display.exposure);  // the panel's still window
    still_shown_.width = result->picture.width;
    still_shown_.height = result->picture.height;
    still_shown_.summary = result->summary;
    still_uploaded_ = result->version;
    still_exposure_ = panel_.display.exposure;
    if (!script_.take_still(*result, panel_.display.exposure, frame)) code_ = exit_input_error;
  }
  still_shown_.running = still_.running();
  still_shown_.progress = still_.progress();
}

panel_actions viewer_app::draw(const worker_view& view, int frame, panel_actions& keys) {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  // A run is recorded under its own settings, and the panel shows the last
  // run made with the settings it holds.
  const std::string setting = setting_key(panel_.solver);
  errors_.observe(view, setting_key(view.settings));
  const error_status error_shown = errors_.status(setting);
  panel_.warning = back_face_warning(back_faces_);
  panel_.current_camera = camera_from_orbit(orbit_, scene_camera_);
  if (width_ > 0 && height_ > 0) {
    panel_.current_camera.width = width_;
    panel_.current_camera.height = height_;
  }
  const panel_actions act = draw_panel(panel_, view, frame_ms_, still_shown_, error_shown);
  ImGui::Render();
  if (width_ <= 0 || height_ <= 0) return act;  // a minimised window draws nothing

  camera cam = camera_from_orbit(orbit_, scene_camera_);
  cam.width = width_;
  cam.height = height_;
  const glm::mat4 view_projection(projection_matrix(cam, bounds(view)) * view_matrix(cam));
  // Before the solution has light of its own, the scene is previewed
  // under a headlight (mid-grey at the exposure shown) rather than black.
  gl::display_settings display = panel_.display;
  const bool lit = uploaded_solution_ && uploaded_solution_->stats.steps > 0;
  display.headlight = lit ? 0.0 : preview_radiance / std::max(display.exposure, 1e-30);
  // The mirrors' and glass's probes follow the solution (docs/viewer.md,
  // "Mirrors and glass"): a first round at once, then faces within a few
  // milliseconds a frame while the solver shoots (a face draws the whole
  // scene, and the solution moves on anyway), more once it has stopped.
  if (view.mesh) {
    const auto probes_start = clock_type::now();
    const double budget_ms = view.running ? 4.0 : 20.0;
    std::size_t faces = !view.running || frame % 4 == 0 ? 1 : 0;
    while (renderer_.refresh_reflections(faces, display.headlight) && faces > 0) {
      glFinish();  // llvmpipe draws on the CPU: the time is the faces'
      if (milliseconds_since(probes_start) >= budget_ms) break;
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, framebuffer_width_, height_);
  glEnable(GL_MULTISAMPLE);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glViewport(0, 0, width_, height_);  // the view: the window left of the panel
  if (view.mesh) renderer_.draw(view_projection, glm::vec3(cam.eye), display);
  if (rest_start_) {
    refiner_.start(view.source, *rest_start_, view.mesh, refined_solution_,
                   read_view_radiance(width_, height_, panel_.display));
    rest_start_.reset();
  }
  if (refined_passes_ > 0) refined_.draw();
  // Automatic exposure from the picture as drawn, once it is lit (the
  // headlit preview follows the exposure, so it cannot set it).
  if (panel_.auto_exposure && lit && !display.wireframe && display.colours == gl::false_colour::none)
    exposure_.update(width_, height_, panel_.display);

  if (script_.wants_still(frame, view.mesh != nullptr)) keys.trace_still = true;
  // A scripted end waits for passes of the solution as it ended: passes of
  // a solve still running are started over once it converges, and a
  // screenshot taken between would show the earlier solution.
  const bool refined_final = refined_solution_ && view.converged && view.solution == refined_solution_;
  const int final_passes = refined_final ? refined_passes_ : 0;
  const bool scripted_end = script_.at_end(frame, error_shown, panel_.refine_at_rest ? final_passes : INT_MAX);
  const bool shoot = act.screenshot || keys.screenshot || (scripted_end && !options_.screenshot_path.empty());
  const bool panel_in_shot = scripted_end ? options_.screenshot_panel : panel_.screenshot_with_panel;
  auto screenshot = [&] {
    const std::string path = scripted_end ? options_.screenshot_path
                             : !panel_.screenshot_path.empty()
                                 ? panel_.screenshot_path
                                 : dated_file_name(shown_source_ ? shown_source_->source : "", "screenshot", ".png");
    std::string e;
    panel_.message = save_screenshot(path, panel_in_shot ? framebuffer_width_ : width_, height_, e)
                         ? "screenshot: " + std::filesystem::absolute(path).string()
                         : e;
    std::printf("%s\n", panel_.message.c_str());
  };
  if (shoot && !panel_in_shot) screenshot();
  if (!options_.screenshots_dir.empty() && options_.screenshot_every > 0 && frame > 0 &&
      (frame == 1 || frame % options_.screenshot_every == 0) && frame <= options_.frames) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.png", frame);
    std::string e;
    if (!save_screenshot((std::filesystem::path(options_.screenshots_dir) / name).string(), width_, height_, e)) {
      std::fprintf(stderr, "error: %s\n", e.c_str());
      code_ = exit_input_error;
    }
  }
  glViewport(0, 0, framebuffer_width_, height_);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (shoot && panel_in_shot) screenshot();
  if (scripted_end) {
    const std::shared_ptr<const worker_view> last = worker_.latest();
    script_.report(error_shown, timing_, width_, height_, last->mesh ? last->mesh->element_count() : 0,
                   last->meshed_elements);
    if (options_.exit_after) glfwSetWindowShouldClose(window_, GLFW_TRUE);
  }
  return act;
}

void viewer_app::refine_at_rest(const worker_view& view) {
  const auto now = clock_type::now();
  // Wireframe and false colour are views of the mesh, not of the light: they stay live.
  const bool refine_wanted =
      panel_.refine_at_rest && !panel_.display.wireframe && panel_.display.colours == gl::false_colour::none;
  const bool moved = !same_view(orbit_, rested_orbit_) || width_ != rested_width_ || height_ != rested_height_ ||
                     view.source != refined_source_;
  // A new solution restarts the passes once the solver has converged (a
  // solve still running would restart them at every step).
  const bool new_solution = view.converged && view.solution != refined_solution_;
  if (moved || !refine_wanted || (new_solution && refiner_.active()) || (view.running && refiner_.active())) {
    refiner_.stop();
    rest_start_.reset();
    refined_passes_ = 0;
    refined_.clear();
    if (moved) last_motion_ = now;
    rested_orbit_ = orbit_;
    rested_width_ = width_;
    rested_height_ = height_;
    refined_source_ = view.source;
    refined_solution_.reset();
  }
  const double rested = std::chrono::duration<double>(now - last_motion_).count();
  // Passes start only once the solver is at rest (converged or paused):
  // passes of a solution still moving were noisier than the live view and
  // were thrown away at every new solution anyway (a million triangles
  // showed noise for more than 30 s).
  if (!refiner_.active() && !rest_start_ && refine_wanted && rested >= rest_seconds && !view.running && view.source &&
      view.mesh && view.solution && view.solution->stats.steps > 0 && width_ > 0 && height_ > 0) {
    camera cam = camera_from_orbit(orbit_, scene_camera_);
    cam.width = width_;
    cam.height = height_;
    rest_start_ = cam;  // started once this frame's live view is drawn: it is read back for the blend
    refined_solution_ = view.solution;
  }
  if (const auto picture = refiner_.picture();
      picture && (picture->passes != refined_passes_ || panel_.display.exposure != refined_exposure_)) {
    refined_.upload(picture->shown, panel_.display.exposure);
    refined_passes_ = picture->passes;
    refined_exposure_ = panel_.display.exposure;
  }
  panel_.refined_passes = refined_passes_;
}

void viewer_app::lead_solver(const worker_view& view) {
  if (!view.source || width_ <= 0 || height_ <= 0) return;
  if (view.source != led_source_) {  // a scene (re)opened: the worker leads it by its own camera
    led_source_ = view.source;
    led_orbit_ = orbit_from_camera(view.source->view);
    led_width_ = view.source->view.width;
    led_height_ = view.source->view.height;
  }
  if (!panel_.solver.view) return;  // view-independent
  const double rested = std::chrono::duration<double>(clock_type::now() - last_motion_).count();
  // The picture's size matters only by its shape: the seen density is of rays across it.
  const bool same_shape = std::int64_t(width_) * led_height_ == std::int64_t(height_) * led_width_;
  if (rested < rest_seconds || (same_view(orbit_, led_orbit_) && same_shape)) return;
  camera cam = camera_from_orbit(orbit_, scene_camera_);
  cam.width = width_;
  cam.height = height_;
  panel_.solver.view = cam;  // reloads keep it
  worker_.set_view(cam);
  led_orbit_ = orbit_;
  led_width_ = width_;
  led_height_ = height_;
}

void viewer_app::carry_out(const panel_actions& act, const worker_view& view) {
  send_to_worker(act, panel_, worker_);  // a reload keeps the scene on the worker: no copy here
  if (act.pause) pause_asked_ = true;
  if (act.resume || act.step || act.restart || act.open_scene || act.apply_mesh) pause_asked_ = false;
  if (act.frame_scene) orbit_frame(orbit_, bounds(view), scene_camera_.fov_y_degrees);
  if (act.reset_camera) orbit_ = orbit_from_camera(scene_camera_);
  if (act.trace_still && view.source && !still_.running()) {
    camera cam = camera_from_orbit(orbit_, scene_camera_);
    if (panel_.still.window_size && width_ > 0 && height_ > 0) {
      cam.width = width_;
      cam.height = height_;
    } else if (panel_.still.size[0] > 0 && panel_.still.size[1] > 0) {
      cam.width = panel_.still.size[0];
      cam.height = panel_.still.size[1];
    }
    still_.start(view.source, cam, view.mesh, view.solution, still_params(panel_.still));
    panel_.message = tracing_message;
  }
  // The reference is of the camera as it is now, 64x64 pixels.
  if ((act.compute_reference || (options_.error_plot && !reference_requested_)) && view.source) {
    errors_.compute_reference(view.source, camera_from_orbit(orbit_, scene_camera_), 64, 1024);
    reference_requested_ = true;
  }
  if (act.cancel_reference) errors_.cancel_reference();
  if (act.cancel_still) {
    still_.cancel();
    panel_.message = "still cancelled";
  }
  if (act.quit) glfwSetWindowShouldClose(window_, GLFW_TRUE);
  if (act.save_layout) save_panel_layout(panel_.layout);
  if (act.save_camera) {
    std::string e;
    panel_.message = write_file(panel_.camera_path, camera_json(panel_.current_camera), e)
                         ? "camera saved: " + std::filesystem::absolute(panel_.camera_path).string() +
                               " (bounce render SCENE --camera FILE)"
                         : e;
  }
  if (view.source && (act.add_bookmark || act.delete_bookmark >= 0)) {
    if (act.add_bookmark)
      panel_.bookmarks.push_back({"view " + std::to_string(panel_.bookmarks.size() + 1), panel_.current_camera});
    if (act.delete_bookmark >= 0 && act.delete_bookmark < int(panel_.bookmarks.size()))
      panel_.bookmarks.erase(panel_.bookmarks.begin() + act.delete_bookmark);
    save_bookmarks(view.source->source, panel_.bookmarks);
  }
  if (act.go_to_bookmark >= 0 && act.go_to_bookmark < int(panel_.bookmarks.size())) {
    const camera& b = panel_.bookmarks[std::size_t(act.go_to_bookmark)].view;
    orbit_ = orbit_from_camera(b);
    scene_camera_.fov_y_degrees = b.fov_y_degrees;
  }
  if (act.bake) panel_.message = bake_shown_solution(view, panel_.bake_path, panel_.display.exposure);
  if ((act.save_still_png || act.save_still_pfm) && still_.result()) {
    const image& picture = still_.result()->picture;
    std::string path = act.save_still_png ? panel_.still.png_path : panel_.still.pfm_path;
    if (path.empty())
      path = dated_file_name(view.source ? view.source->source : "", "still", act.save_still_png ? ".png" : ".pfm");
    std::string e;
    bool ok = true;
    if (act.save_still_png) {
      const std::vector<unsigned char> rows = to_srgb_rows(picture, panel_.display.exposure);
      ok = write_png(path, picture.width, picture.height, 3, rows.data(), e);
    } else {
      ok = write_pfm(path, picture, e);
    }
    panel_.still_message = ok ? "saved " + std::filesystem::absolute(path).string() : e;
  }
  if (act.open_scene || act.apply_mesh) panel_.message.clear();
}

int viewer_app::run() {
  auto last_frame = clock_type::now();
  for (int frame = 1; code_ == exit_ok && !glfwWindowShouldClose(window_); ++frame) {
    glfwPollEvents();
    deliver_input(window_, input_);
    const auto now = clock_type::now();
    const double dt = std::chrono::duration<double>(now - last_frame).count();
    frame_ms_ = 1000.0 * dt;
    last_frame = now;

    std::shared_ptr<const worker_view> view = worker_.latest();
    // A pause takes effect in the window at once: the worker ends the step
    // under way (it cannot stop inside one) and starts no other, and the
    // window shows it paused from the frame Space was pressed.
    if (pause_asked_ && !view->running) pause_asked_ = false;  // the worker has paused
    if (pause_asked_) {
      auto paused = std::make_shared<worker_view>(*view);
      paused->running = false;
      view = std::move(paused);
    }
    if (!view->mesh) frame = 0;  // scripted frames count from the first picture of the scene
    take_published_work(*view);
    take_still(frame);
    timing_.frame(frame, frame_ms_);

    // Input: ImGui first; the view gets what the panel does not want.
    int window_width = 0, window_height = 0;
    glfwGetWindowSize(window_, &window_width, &window_height);
    const std::shared_ptr<const scene_rays> picking = std::atomic_load(&picking_);
    view_frame frame_of_view;
    frame_of_view.base = scene_camera_;
    frame_of_view.width =
        std::max(0, window_width - int(std::lround(docked_width(panel_.layout, float(window_width)))));
    frame_of_view.height = window_height;
    const bounds3& box = bounds(*view);
    frame_of_view.scene_size = glm::length(box.max - box.min);
    frame_of_view.scene = picking && picking->source == view->source ? &picking->rays : nullptr;
    panel_actions keys =
        handle_input(window_, input_, pointer_, orbit_, frame_of_view, view->running, still_.running(), dt, panel_);
    if (!input_.dropped.empty()) {  // a file dropped on the window opens like the panel's Open
      panel_.scene_path = input_.dropped.back();
      input_.dropped.clear();
      keys.open_scene = true;
    }
    glfwGetFramebufferSize(window_, &framebuffer_width_, &height_);
    const double pixels_per_point = window_width > 0 ? double(framebuffer_width_) / window_width : 1.0;
    width_ = std::max(
        0, framebuffer_width_ - int(std::lround(docked_width(panel_.layout, float(window_width)) * pixels_per_point)));
    refine_at_rest(*view);
    lead_solver(*view);
    const panel_actions act = draw(*view, frame, keys);
    glfwSwapBuffers(window_);
    if (uploaded_mesh_ && timing_.first_mesh_ms < 0.0) timing_.first_mesh_ms = milliseconds_since(started_);
    if (uploaded_solution_ && uploaded_solution_->stats.steps > 0 && timing_.first_lit_ms < 0.0)
      timing_.first_lit_ms = milliseconds_since(started_);
    carry_out(either(act, keys), *view);
  }
  return code_;
}

}  // namespace

int run_viewer(const scene& initial, const solver_settings& solver, const viewer_options& options) {
  // The view at the scene camera's aspect, at least 900 pixels on the long
  // side, and the panel docked beside it.
  const double grow = std::max(1.0, 900.0 / std::max(initial.view.width, initial.view.height));
  const int view_width = int(initial.view.width * grow), view_height = int(initial.view.height * grow);
  const panel_layout layout = read_panel_layout();
  const int panel_width = int(std::lround(docked_width(layout, 1e9f)));
  window_input input;
  std::string error;
  GLFWwindow* window = open_window(view_width + panel_width, view_height, options.msaa, input, error);
  if (!window) {
    std::fprintf(stderr, "error: %s\n", error.c_str());
    return exit_input_error;
  }
  glfwSwapInterval(options.frames > 0 ? 0 : 1);  // vsync, except in scripted runs
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui_ImplGlfw_InitForOpenGL(window, false);  // the window's callbacks queue; deliver_input calls ImGui's
  ImGui_ImplOpenGL3_Init("#version 330 core");
  int code = exit_ok;
  {
    viewer_app app(window, input, initial, solver, options);
    code = app.run();
    if (app.working()) {
      // Quitting is immediate: a solver step on a large scene, a still or
      // a reference can take seconds to reach a point where it can stop,
      // and none of them has anything to save (files are written whole
      // when asked for). The window goes at once and the process ends
      // without waiting for them.
      glfwHideWindow(window);
      glfwPollEvents();
      std::fprintf(stderr, "bounce: quit without waiting for the work under way\n");
      std::fflush(nullptr);
      std::_Exit(code);
    }
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  close_window(window);
  return code;
}

}  // namespace bounce
