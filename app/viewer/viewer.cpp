#include "viewer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <glad/gl.h>
// glad first: GLFW must not pull in a GL header of its own.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "camera_math.h"
#include "error_tracker.h"
#include "image.h"
#include "mesh_renderer.h"
#include "orbit.h"
#include "panel.h"
#include "scene_io.h"
#include "solver_worker.h"
#include "still_job.h"

namespace bounce {
namespace {

struct input_state {
  double scroll = 0.0;  // wheel steps since the last frame
};

void on_scroll(GLFWwindow* window, double, double dy) {
  static_cast<input_state*>(glfwGetWindowUserPointer(window))->scroll += dy;
}

void on_glfw_error(int code, const char* message) {
  std::fprintf(stderr, "glfw error %d: %s\n", code, message);
}

// Reads the back buffer (width x height) as RGB, top row first, and writes a PNG.
bool save_screenshot(const std::string& path, int width, int height, std::string& error) {
  std::vector<unsigned char> rgb(std::size_t(width) * height * 3), flipped(rgb.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  const std::size_t row = std::size_t(width) * 3;
  for (int y = 0; y < height; ++y)
    std::copy_n(rgb.data() + std::size_t(height - 1 - y) * row, row, flipped.data() + std::size_t(y) * row);
  return write_png(path, width, height, 3, flipped.data(), error);
}

// The finished still as an sRGB texture for the panel's image window.
void upload_still(unsigned& texture, const image& picture, double exposure) {
  if (!texture) glGenTextures(1, &texture);
  const std::vector<unsigned char> rows = to_srgb_rows(picture, exposure);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, picture.width, picture.height, 0, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
}

trace_params still_params(const still_settings& settings) {
  trace_params p;
  p.method = settings.integrator == 1 ? integrator::path : integrator::whitted;
  p.spp = std::max(1, settings.spp);
  p.diffuse = settings.direct == 1 ? diffuse_source::radiosity : diffuse_source::traced_direct;
  return p;
}

}  // namespace

int run_viewer(const scene& initial, const solver_settings& solver, const viewer_options& options) {
  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit()) {
    std::fprintf(stderr, "error: no display for a window (GLFW could not start); use `bounce render` instead\n");
    return exit_input_error;
  }
  // The scene camera's aspect, at least 900 pixels on the long side so the
  // panel leaves room for the view.
  const double grow = std::max(1.0, 900.0 / std::max(initial.view.width, initial.view.height));
  auto open_window = [&](int samples) {
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SAMPLES, samples);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
    GLFWwindow* w =
        glfwCreateWindow(int(initial.view.width * grow), int(initial.view.height * grow), "Bounce", nullptr, nullptr);
    if (w) {
      glfwMakeContextCurrent(w);
      if (!gladLoadGL(glfwGetProcAddress)) {
        glfwDestroyWindow(w);
        w = nullptr;
      }
    }
    return w;
  };
  // Antialiasing: 4x MSAA on a GPU. Mesa's llvmpipe renders on the CPU,
  // where 4x MSAA doubles the frame time (measured 63 ms against 29 ms per
  // frame at 1280x720 while solving): there the window goes without, so the
  // UI stays under 33 ms a frame; --msaa forces either. Headless pictures
  // always use 4x MSAA.
  GLFWwindow* window = open_window(options.msaa < 0 ? 4 : options.msaa);
  if (window && options.msaa < 0) {
    const char* renderer_name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string name = renderer_name ? renderer_name : "";
    if (name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos) {
      glfwDestroyWindow(window);
      window = open_window(0);
      std::printf("bounce: software OpenGL (%s): window antialiasing off to keep frames fast (--msaa 4 forces it)\n",
                  name.c_str());
    }
  }
  if (!window) {
    glfwTerminate();
    std::fprintf(stderr, "error: cannot open a GL 3.3 core window\n");
    return exit_input_error;
  }
  input_state input;
  glfwSetWindowUserPointer(window, &input);
  glfwSetScrollCallback(window, on_scroll);      // before ImGui, which chains to it
  glfwSwapInterval(options.frames > 0 ? 0 : 1);  // vsync, except in scripted runs
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");

  int code = exit_ok;
  {
    gl::mesh_renderer renderer;
    std::string error;
    if (!renderer.init(error)) {
      std::fprintf(stderr, "error: %s", error.c_str());
      code = exit_input_error;
    }
    solver_worker worker;
    worker.load(initial, solver);
    if (options.start_paused) worker.pause();
    // Frame and upload timings, reported after a scripted run.
    double frame_ms_sum = 0.0, upload_ms_sum = 0.0, upload_ms_max = 0.0;
    int frames_timed = 0, uploads = 0;
    panel_state panel;
    panel.scene_path = initial.source;
    panel.solver = solver;
    panel.asset_scenes = find_scenes("assets");
    if (!options.still_path.empty()) {  // a scripted still has the scene camera's --size
      panel.still.window_size = false;
      panel.still.size[0] = initial.view.width;
      panel.still.size[1] = initial.view.height;
    }
    camera scene_camera = initial.view;
    orbit_state orbit = orbit_from_camera(scene_camera);
    std::shared_ptr<const patch_mesh> uploaded_mesh;
    std::shared_ptr<const scene> shown_source;
    std::uint64_t uploaded_version = ~0ull;
    double last_x = 0, last_y = 0;
    glfwGetCursorPos(window, &last_x, &last_y);
    auto last_frame = std::chrono::steady_clock::now();
    double frame_ms = 0.0;
    std::string shown_error;
    // The ray-traced still: traced on its own thread, shown as a texture.
    still_job still;
    still_status still_shown;
    std::uint64_t still_uploaded = 0;
    double still_exposure = 0.0;
    int still_saved_frame = -1;  // scripted run: the frame the still was written in
    // Error against time: a path-traced reference of the camera on request.
    error_tracker errors;
    bool reference_requested = false;

    for (int frame = 1; code == exit_ok && !glfwWindowShouldClose(window); ++frame) {
      glfwPollEvents();
      const auto now = std::chrono::steady_clock::now();
      const double dt = std::chrono::duration<double>(now - last_frame).count();
      frame_ms = 1000.0 * dt;
      last_frame = now;

      // Newest published work: a new mesh is uploaded once, then only the
      // radiosity buffer changes.
      const std::shared_ptr<const worker_view> view = worker.latest();
      if (!view->mesh) frame = 0;                       // scripted frames count from the first picture of the scene
      if (view->mesh && view->mesh != uploaded_mesh) {  // a new scene, density or refinement pass
        renderer.upload(*view->mesh);
        uploaded_mesh = view->mesh;
        uploaded_version = ~0ull;
      }
      if (view->source != shown_source) {
        if (shown_source) {  // a newly opened scene brings its camera
          scene_camera = view->source->view;
          orbit = orbit_from_camera(scene_camera);
        }
        shown_source = view->source;
      }
      if (view->solution && view->solution->version != uploaded_version) {
        const auto upload_start = std::chrono::steady_clock::now();
        renderer.update(*view->solution);
        glFinish();  // llvmpipe copies on the CPU: finish so the time is the upload's
        const double upload_ms =
            1000.0 * std::chrono::duration<double>(std::chrono::steady_clock::now() - upload_start).count();
        upload_ms_sum += upload_ms;
        upload_ms_max = std::max(upload_ms_max, upload_ms);  // a refined mesh's upload, with adaptive meshing
        ++uploads;
        uploaded_version = view->solution->version;
      }
      if (const auto result = still.result();
          result && (result->version != still_uploaded || panel.display.exposure != still_exposure)) {
        upload_still(still_shown.texture, result->picture, panel.display.exposure);
        still_shown.width = result->picture.width;
        still_shown.height = result->picture.height;
        still_shown.summary = result->summary;
        still_uploaded = result->version;
        still_exposure = panel.display.exposure;
        if (!options.still_path.empty() && still_saved_frame < 0) {
          std::string e;
          const std::vector<unsigned char> rows = to_srgb_rows(result->picture, panel.display.exposure);
          const bool saved =
              write_png(options.still_path, result->picture.width, result->picture.height, 3, rows.data(), e);
          std::printf("%s\n",
                      saved ? ("still: " + result->summary + ", wrote " + options.still_path).c_str() : e.c_str());
          if (!saved) code = exit_input_error;
          still_saved_frame = frame;
        }
      }
      still_shown.running = still.running();
      still_shown.progress = still.progress();
      if (frame > 10) {  // past start-up (mesh upload, font atlas)
        frame_ms_sum += frame_ms;
        ++frames_timed;
      }
      if (view->error != shown_error) {
        shown_error = view->error;
        if (!shown_error.empty()) std::fprintf(stderr, "error: %s\n", shown_error.c_str());
      }

      // Input: ImGui first; the view gets what the panel does not want.
      ImGuiIO& io = ImGui::GetIO();
      double x = 0, y = 0;
      glfwGetCursorPos(window, &x, &y);
      const double dx = x - last_x, dy = y - last_y;
      last_x = x;
      last_y = y;
      int window_width = 0, window_height = 0;
      glfwGetWindowSize(window, &window_width, &window_height);
      const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
      if (!io.WantCaptureMouse) {
        const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                           glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
        if (right || (left && shift))
          orbit_pan(orbit, dx, dy, window_height, scene_camera.fov_y_degrees);
        else if (left)
          orbit_rotate(orbit, dx, dy);
        if (input.scroll != 0.0) orbit_zoom(orbit, input.scroll);
      }
      input.scroll = 0.0;
      panel_actions keys;
      if (!io.WantCaptureKeyboard) {
        auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
        const double speed = orbit.distance * 0.5 * dt;  // half the viewing distance per second
        orbit_fly(orbit, (down(GLFW_KEY_W) - down(GLFW_KEY_S)) * speed, (down(GLFW_KEY_D) - down(GLFW_KEY_A)) * speed,
                  (down(GLFW_KEY_E) - down(GLFW_KEY_Q)) * speed);
        for (int k = 0; k < int(io.InputQueueCharacters.Size); ++k) {
          switch (io.InputQueueCharacters[k]) {
            case 'f':
            case 'F':
              keys.frame_scene = true;
              break;
            case 'c':
            case 'C':
              keys.reset_camera = true;
              break;
            case ' ':
              (view->running ? keys.pause : keys.resume) = true;
              break;
            case 'n':
            case 'N':
              keys.step = true;
              break;
            case 'r':
            case 'R':
              keys.restart = true;
              break;
            case 'g':
            case 'G':
              panel.display.wireframe = !panel.display.wireframe;
              break;
            case 'p':
            case 'P':
              keys.screenshot = true;
              break;
            case 't':
            case 'T':
              keys.trace_still = true;
              break;
            case 'h':
            case 'H':
              panel.show_help = !panel.show_help;
              break;
            default:
              break;
          }
        }
        if (down(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window, GLFW_TRUE);
      }

      // The 3-D view; a minimised window (size 0) draws nothing.
      int width = 0, height = 0;
      glfwGetFramebufferSize(window, &width, &height);
      ImGui_ImplOpenGL3_NewFrame();
      ImGui_ImplGlfw_NewFrame();
      ImGui::NewFrame();
      const std::string setting = setting_key(panel.solver);
      errors.observe(*view, setting);
      const error_status error_shown = errors.status(setting);
      panel_actions act = draw_panel(panel, *view, frame_ms, still_shown, error_shown);
      ImGui::Render();
      if (width > 0 && height > 0) {
        camera cam = camera_from_orbit(orbit, scene_camera);
        cam.width = width;
        cam.height = height;
        const bounds3 bounds = view->source ? scene_bounds(*view->source) : scene_bounds(initial);
        const glm::mat4 view_projection(projection_matrix(cam, bounds) * view_matrix(cam));
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, width, height);
        glEnable(GL_MULTISAMPLE);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        if (view->mesh) renderer.draw(view_projection, glm::vec3(cam.eye), panel.display);
        // A scripted still starts halfway and the run waits for it.
        if (!options.still_path.empty() && frame == std::max(1, options.frames / 2) && view->mesh)
          keys.trace_still = true;
        // ... and for its window to appear (ImGui lays new windows out over a frame or two).
        const bool still_pending =
            !options.still_path.empty() && (still_saved_frame < 0 || frame < still_saved_frame + 3);
        // ... and, with --error-plot, for the reference and a first measurement.
        const bool error_pending = options.error_plot && (!error_shown.ready || error_shown.history.empty());
        const bool scripted_end = options.frames > 0 && frame >= options.frames && !still_pending && !error_pending;
        auto screenshot = [&](const std::string& path) {
          std::string e;
          if (save_screenshot(path, width, height, e))
            panel.message = "screenshot: " + std::filesystem::absolute(path).string();
          else
            panel.message = e;
          std::printf("%s\n", panel.message.c_str());
        };
        const bool panel_in_shot = scripted_end ? options.screenshot_panel : panel.screenshot_with_panel;
        if ((act.screenshot || keys.screenshot || (scripted_end && !options.screenshot_path.empty())) && !panel_in_shot)
          screenshot(scripted_end ? options.screenshot_path : panel.screenshot_path);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if ((act.screenshot || keys.screenshot || (scripted_end && !options.screenshot_path.empty())) && panel_in_shot)
          screenshot(scripted_end ? options.screenshot_path : panel.screenshot_path);
        if (scripted_end && options.error_plot) {
          if (error_shown.history.empty())
            std::printf("error plot: no measurement yet (%s)\n", error_shown.summary.c_str());
          else
            std::printf("error plot: %zu measurements; error %.4f at %.3f s, %.4f at %.3f s (%s)\n",
                        error_shown.history.size(), error_shown.history.front().error,
                        error_shown.history.front().seconds, error_shown.history.back().error,
                        error_shown.history.back().seconds, error_shown.summary.c_str());
        }
        if (scripted_end && frames_timed > 0) {
          const std::shared_ptr<const worker_view> last = worker.latest();
          std::printf(
              "view: %dx%d, %zu triangles (%zu as meshed), %d frames: %.2f ms per frame (%.1f fps); radiosity upload "
              "%.3f ms (mean of %d, largest %.2f ms)\n",
              width, height, last->mesh ? last->mesh->element_count() : 0, last->meshed_elements, frames_timed,
              frame_ms_sum / frames_timed, 1000.0 * frames_timed / frame_ms_sum,
              uploads ? upload_ms_sum / uploads : 0.0, uploads, upload_ms_max);
        }
        if (scripted_end && options.exit_after) glfwSetWindowShouldClose(window, GLFW_TRUE);
      }
      glfwSwapBuffers(window);

      // Carry out what the panel and the keys asked for.
      if (act.open_scene) worker.load_file(panel.scene_path, panel.solver);
      if (act.apply_mesh && view->source) worker.load(*view->source, panel.solver);
      if (act.pause || keys.pause) worker.pause();
      if (act.resume || keys.resume) worker.resume();
      if (act.step || keys.step) worker.step();
      if (act.restart || keys.restart) {
        worker.restart();
        worker.resume();
      }
      if (act.frame_scene || keys.frame_scene)
        orbit_frame(orbit, view->source ? scene_bounds(*view->source) : scene_bounds(initial),
                    scene_camera.fov_y_degrees);
      if (act.reset_camera || keys.reset_camera) orbit = orbit_from_camera(scene_camera);
      if ((act.trace_still || keys.trace_still) && view->source && !still.running()) {
        camera cam = camera_from_orbit(orbit, scene_camera);
        if (panel.still.window_size && width > 0 && height > 0) {
          cam.width = width;
          cam.height = height;
        } else if (panel.still.size[0] > 0 && panel.still.size[1] > 0) {
          cam.width = panel.still.size[0];
          cam.height = panel.still.size[1];
        }
        still.start(view->source, cam, view->mesh, view->solution, still_params(panel.still));
        panel.message = "tracing a still...";
      }
      // The reference is of the camera as it is now, 64x64 pixels.
      if ((act.compute_reference || (options.error_plot && !reference_requested)) && view->source) {
        errors.compute_reference(view->source, camera_from_orbit(orbit, scene_camera), 64, 1024);
        reference_requested = true;
      }
      if (act.cancel_still) {
        still.cancel();
        panel.message = "still cancelled";
      }
      if ((act.save_still_png || act.save_still_pfm) && still.result()) {
        const image& picture = still.result()->picture;
        std::string e;
        bool ok = true;
        if (act.save_still_png) {
          const std::vector<unsigned char> rows = to_srgb_rows(picture, panel.display.exposure);
          ok = write_png(panel.still.png_path, picture.width, picture.height, 3, rows.data(), e);
        } else {
          ok = write_pfm(panel.still.pfm_path, picture, e);
        }
        panel.message =
            ok ? "saved " + std::filesystem::absolute(act.save_still_png ? panel.still.png_path : panel.still.pfm_path)
                                .string()
               : e;
      }
      if ((act.open_scene || act.apply_mesh)) panel.message.clear();
    }
    if (still_shown.texture) glDeleteTextures(1, &still_shown.texture);
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace bounce
