#include "cli.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench_command.h"
#include "image_metrics.h"
#include "render_command.h"
#include "scene_info.h"
#include "scene_io.h"
#include "solve_command.h"
#include "trace_command.h"
#include "viewer.h"

namespace bounce {
namespace {

bool parse_double(std::string_view text, double& value) {
  // from_chars has no leading '+'; accept it like strtod does.
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

void print_warnings(const load_report& report) {
  for (const std::string& w : report.warnings) std::cerr << "warning: " << w << "\n";
  if (report.dropped_faces) std::cerr << "warning: " << report.dropped_faces << " degenerate face(s) dropped\n";
}

// Loads the scene named on the command line (or the embedded default) and
// applies the camera overrides. Prints the error and returns false on failure.
bool load_for_command(const std::string& path, const camera_options* camera_overrides, scene& s) {
  load_report report;
  if (!load_scene(path.empty() ? default_scene_path : path, s, report)) {
    std::cerr << "error: " << report.error << "\n";
    return false;
  }
  print_warnings(report);
  if (camera_overrides) {
    if (std::string e = apply_camera_options(*camera_overrides, s.view); !e.empty()) {
      std::cerr << "error: " << e << "\n";
      return false;
    }
  }
  return true;
}

std::string format_vec3(const vec3& v) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, "(%.6g, %.6g, %.6g)", v.x, v.y, v.z);
  return buffer;
}

int run_info(const std::string& path, bool as_json, double max_edge) {
  scene s;
  if (!load_for_command(path, nullptr, s)) return exit_input_error;
  if (max_edge < 0.0) {
    std::cerr << "error: --max-edge must be positive\n";
    return exit_usage;
  }
  double edge = max_edge > 0.0 ? max_edge : default_max_edge(s);
  scene_summary sum;
  if (std::string e = summarize_scene(s, edge, sum); !e.empty()) {
    std::cerr << "error: " << s.source << ": " << e << "\n";
    return exit_input_error;
  }
  if (as_json) {
    nlohmann::json j = {
        {"scene", s.source},
        {"surfaces", sum.surfaces},
        {"polygon_meshes", sum.polygon_meshes},
        {"spheres", sum.spheres},
        {"quadrics", sum.quadrics},
        {"bezier_surfaces", sum.bezier_surfaces},
        {"bspline_surfaces", sum.bspline_surfaces},
        {"polygons", sum.polygons},
        {"patches", sum.patches},
        {"triangles", sum.triangles},
        {"max_edge", sum.max_edge},
        {"materials", sum.materials},
        {"textures", sum.textures},
        {"emitting_materials", sum.emitting_materials},
        {"emitting_surfaces", sum.emitting_surfaces},
        {"point_lights", sum.point_lights},
        {"bounds",
         {{"min", {sum.bounds.min.x, sum.bounds.min.y, sum.bounds.min.z}},
          {"max", {sum.bounds.max.x, sum.bounds.max.y, sum.bounds.max.z}}}},
        {"camera",
         {{"eye", {s.view.eye.x, s.view.eye.y, s.view.eye.z}},
          {"target", {s.view.target.x, s.view.target.y, s.view.target.z}},
          {"up", {s.view.up.x, s.view.up.y, s.view.up.z}},
          {"fov", s.view.fov_y_degrees},
          {"size", {s.view.width, s.view.height}}}},
    };
    std::cout << j.dump(2) << "\n";
    return exit_ok;
  }
  std::cout << "scene:      " << s.source << "\n"
            << "surfaces:   " << sum.surfaces << " (polygon meshes " << sum.polygon_meshes << ", spheres "
            << sum.spheres << ", quadrics " << sum.quadrics << ", Bezier " << sum.bezier_surfaces << ", B-spline "
            << sum.bspline_surfaces << ")\n"
            << "polygons:   " << sum.polygons << "\n"
            << "patches:    " << sum.patches << " (Bezier patches + B-spline spans)\n"
            << "triangles:  " << sum.triangles << " (curved surfaces tessellated at max edge " << sum.max_edge << ")\n"
            << "materials:  " << sum.materials << " (" << sum.emitting_materials << " emitting), textures "
            << sum.textures << "\n"
            << "emitters:   " << sum.emitting_surfaces << " surface(s), " << sum.point_lights << " point light(s)\n"
            << "bounds:     " << format_vec3(sum.bounds.min) << " to " << format_vec3(sum.bounds.max) << "\n"
            << "camera:     eye " << format_vec3(s.view.eye) << ", target " << format_vec3(s.view.target) << ", fov "
            << s.view.fov_y_degrees << ", " << s.view.width << "x" << s.view.height << "\n";
  return exit_ok;
}

int run_compare(const std::string& test_path, const std::string& reference_path, int factor, double bright) {
  image test, reference;
  std::string error;
  if (!read_pfm(test_path, test, error) || !read_pfm(reference_path, reference, error)) {
    std::cerr << "error: " << error << "\n";
    return exit_input_error;
  }
  if (test.width != reference.width || test.height != reference.height) {
    std::cerr << "error: " << test_path << " is " << test.width << "x" << test.height << " but " << reference_path
              << " is " << reference.width << "x" << reference.height << "\n";
    return exit_input_error;
  }
  if (bright > 0.0) {
    const std::vector<bool> emitters = bright_pixels(reference, bright);
    exclude_pixels(test, emitters, 1);
    exclude_pixels(reference, emitters, 1);
  }
  test = downsample(test, factor);
  reference = downsample(reference, factor);
  std::printf("mean radiance: test %.6g, reference %.6g (ratio %.5f)\n", mean_radiance(test), mean_radiance(reference),
              mean_radiance(test) / mean_radiance(reference));
  std::printf("relative RMSE %.5f, mean relative error %.5f, max relative error %.4f (%dx%d after %dx downsampling)\n",
              relative_rmse(test, reference), mean_relative_error(test, reference), max_relative_error(test, reference),
              test.width, test.height, factor);
  return exit_ok;
}

}  // namespace

std::optional<vec3> parse_vec3(const std::string& text) {
  vec3 v;
  std::size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    std::size_t comma = text.find(',', start);
    bool last = i == 2;
    if (last != (comma == std::string::npos)) return std::nullopt;
    std::string_view part = std::string_view(text).substr(start, last ? std::string::npos : comma - start);
    if (!parse_double(part, v[i])) return std::nullopt;
    start = comma + 1;
  }
  return v;
}

std::optional<std::pair<int, int>> parse_size(const std::string& text) {
  std::size_t x = text.find('x');
  if (x == std::string::npos) return std::nullopt;
  int w = 0, h = 0;
  auto [e1, c1] = std::from_chars(text.data(), text.data() + x, w);
  auto [e2, c2] = std::from_chars(text.data() + x + 1, text.data() + text.size(), h);
  if (c1 != std::errc() || e1 != text.data() + x || c2 != std::errc() || e2 != text.data() + text.size())
    return std::nullopt;
  return std::pair{w, h};
}

std::string apply_camera_options(const camera_options& options, camera& view) {
  camera c = view;
  const std::pair<const char*, const std::string*> vectors[] = {
      {"--eye", &options.eye}, {"--target", &options.target}, {"--up", &options.up}};
  vec3* fields[] = {&c.eye, &c.target, &c.up};
  for (int i = 0; i < 3; ++i) {
    if (vectors[i].second->empty()) continue;
    auto v = parse_vec3(*vectors[i].second);
    if (!v) return std::string(vectors[i].first) + ": expected x,y,z (three numbers), got '" + *vectors[i].second + "'";
    *fields[i] = *v;
  }
  if (options.fov) {
    if (!(*options.fov > 0.0 && *options.fov < 180.0)) return "--fov: must be in (0, 180) degrees";
    c.fov_y_degrees = *options.fov;
  }
  if (!options.size.empty()) {
    auto size = parse_size(options.size);
    if (!size) return "--size: expected WxH, got '" + options.size + "'";
    c.width = size->first;
    c.height = size->second;
  }
  // The same rules as a scene file's camera.
  scene probe;
  probe.view = c;
  probe.lights.push_back({vec3(0.0), rgb(1.0)});
  probe.materials.push_back({});
  probe.surfaces.push_back({"probe", "", sphere{}});
  if (std::string e = validate_scene(probe); !e.empty()) return "camera override: " + e;
  view = c;
  return {};
}

void add_solver_options(CLI::App& command, solver_settings& o) {
  std::map<std::string, form_factor_method> methods;
  for (const auto& m : form_factor_method_names()) methods.emplace(std::string(m.name), m.method);
  command.add_option("--method", o.form_factors.method, "form-factor method")
      ->transform(CLI::CheckedTransformer(methods, CLI::ignore_case))
      ->default_str(std::string(name_of(o.form_factors.method)));
  command.add_option("--max-edge", o.max_edge, "longest element edge, scene units (default: diagonal/24)")
      ->check(CLI::PositiveNumber);
  command.add_option("--until", o.stop.unshot_fraction, "stop when the unshot power fraction falls below this")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command.add_option("--max-shots", o.stop.max_shots, "stop after this many shots")->check(CLI::NonNegativeNumber);
  command.add_option("--time", o.stop.seconds, "stop after this many seconds of solving")
      ->check(CLI::NonNegativeNumber);
  command
      .add_option("--patch-edge", o.patch_edge,
                  "size of the shooting patches over the elements (substructuring); default 4 x max edge, "
                  "0: every element shoots (exact)")
      ->check(CLI::NonNegativeNumber);
  command.add_flag_callback(
      "--full-rays", [&o] { o.form_factors.adaptive_rays = false; },
      "raycast: cast every shadow ray, without the 2x2 visibility probe");
  command
      .add_option("--rays", o.form_factors.shadow_rays,
                  "raycast: shadow rays per receiver and shooter (rounded up to a square)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command.add_option("--hemicube", o.form_factors.hemicube_resolution, "hemicube: resolution of the top face")
      ->check(CLI::Range(8, 4096))
      ->capture_default_str();
  command.add_flag("--adaptive", o.adaptive.enabled,
                   "adaptive meshing: refine at contacts and near emitters, then where the radiosity changes "
                   "and along shadow edges while solving");
  command
      .add_option("--tolerance", o.adaptive.tolerance,
                  "adaptive: split where vertex radiosities differ by this fraction")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  command
      .add_option("--min-edge", o.adaptive.min_edge,
                  "adaptive: elements whose longest edge is at most this are not split (default: max edge / 8)")
      ->check(CLI::PositiveNumber);
}

void add_camera_options(CLI::App& command, camera_options& o) {
  command.add_option("--eye", o.eye, "camera position x,y,z");
  command.add_option("--target", o.target, "point looked at x,y,z");
  command.add_option("--up", o.up, "up direction x,y,z");
  command.add_option("--fov", o.fov, "vertical field of view, degrees");
  command.add_option("--size", o.size, "image size WxH");
}

int run_cli(int argc, char** argv) {
  CLI::App app{
      "Bounce: progressive radiosity with a live Gouraud view and two-pass ray-traced stills.\n"
      "SCENE is a .json scene or a bare .obj; without one, the embedded Cornell box."};
  app.require_subcommand(0, 1);

  std::string scene_path;
  bool as_json = false;
  double info_max_edge = 0.0;
  CLI::App* info = app.add_subcommand("info", "load and validate a scene, print its counts");
  info->add_option("SCENE", scene_path, "scene file (.json or .obj)");
  info->add_flag("--json", as_json, "machine-readable output");
  info->add_option("--max-edge", info_max_edge, "tessellation size for curved surfaces")->check(CLI::PositiveNumber);

  struct solving_command {
    const char* name;
    const char* help;
    CLI::App* app = nullptr;
    std::string scene;
    solver_settings solver;
    camera_options camera;
  };
  solving_command commands[] = {
      {"view", "open the interactive window", nullptr, {}, {}, {}},
      {"render", "solve and render the Gouraud view headlessly to PNG/PFM", nullptr, {}, {}, {}},
      {"trace", "solve, then ray trace a still (two-pass), or path trace a reference", nullptr, {}, {}, {}},
      {"solve", "run the radiosity solver and report statistics", nullptr, {}, {}, {}},
  };
  for (solving_command& c : commands) {
    c.app = app.add_subcommand(c.name, c.help);
    c.app->add_option("SCENE", c.scene, "scene file (.json or .obj)");
    add_solver_options(*c.app, c.solver);
    add_camera_options(*c.app, c.camera);
  }
  render_options render_extra;
  CLI::App* render = commands[1].app;
  render->add_option("--out", render_extra.png_path, "PNG of the Gouraud view (tone-mapped)")->capture_default_str();
  render->add_option("--pfm", render_extra.pfm_path, "PFM of the same view in linear radiance, unscaled");
  render->add_option("--frames", render_extra.frames_dir, "also write one PNG per --frame-every shots into DIR");
  render->add_option("--frame-every", render_extra.frame_every, "shots between frames")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  render->add_option("--exposure", render_extra.exposure, "displayed value = radiance x exposure")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  render->add_option("--tone", render_extra.curve, "tone curve")
      ->check(CLI::IsMember({"srgb", "filmic"}))
      ->capture_default_str();
  render->add_flag("--wireframe", render_extra.wireframe, "draw element edges");
  render->add_option("--stats", render_extra.stats_path, "write solver statistics as JSON to this file");
  render->add_flag("--ambient", render_extra.ambient, "add the ambient term of the unshot power (display only)");
  render->add_flag("--panel", render_extra.panel, "draw the ImGui panel over the view, as in the window");
  render->add_option("--colours", render_extra.colours, "radiance, or false colour of unshot power or element size")
      ->check(CLI::IsMember({"radiance", "unshot", "size"}))
      ->capture_default_str();
  viewer_options view_extra;
  CLI::App* view = commands[0].app;
  view->add_option("--frames", view_extra.frames, "scripted run: draw this many frames")->check(CLI::PositiveNumber);
  view->add_option("--screenshot", view_extra.screenshot_path, "after the scripted frames, save the window as PNG");
  view->add_option(
      "--still", view_extra.still_path,
      "scripted run: ray trace a still at --size halfway through (as the panel's button does), save it as PNG");
  view->add_flag("--error-plot", view_extra.error_plot,
                 "path trace a 64x64 reference of the camera at the start and plot the error against it");
  view->add_flag("--exit", view_extra.exit_after, "quit after the scripted frames");
  view->add_flag("--paused", view_extra.start_paused, "mesh and show the scene but start the solver paused");
  view->add_option("--msaa", view_extra.msaa, "window antialiasing samples (default: 4 on a GPU, 0 on software GL)")
      ->check(CLI::Range(0, 16));
  trace_options trace_extra;
  add_trace_options(*commands[2].app, trace_extra);
  commands[2].app->add_option("--stats", trace_extra.stats_path,
                              "write trace statistics (and the radiosity pass's) as JSON to this file");
  solve_options solve_extra;
  commands[3].app->add_option("--ply", solve_extra.ply_path, "write the patch mesh with per-vertex radiosity as PLY");
  commands[3].app->add_option("--stats", solve_extra.stats_path, "write solver statistics as JSON to this file");
  commands[3].app->add_flag("--reference", solve_extra.reference,
                            "also solve the full matrix (small scenes) and report the difference");
  commands[3].app->add_flag("--ray-baseline", solve_extra.ray_baseline,
                            "replay 2M of the solver's shadow rays through Embree's rtcOccluded1 and compare rates");
  CLI::App* bench = app.add_subcommand("bench", "measure speed against error: every method on every bench scene");
  bench_options bench_extra;
  add_bench_options(*bench, bench_extra);
  CLI::App* compare = app.add_subcommand("compare", "error of one PFM picture against a reference PFM");
  std::string compare_test, compare_reference;
  int compare_downsample = 1;
  compare->add_option("TEST", compare_test, "picture to measure (PFM)")->required();
  compare->add_option("REFERENCE", compare_reference, "reference picture (PFM), the same size")->required();
  double compare_bright = 0.0;
  compare
      ->add_option("--exclude-above", compare_bright,
                   "leave out pixels (and their neighbours) where the reference exceeds this radiance: emitters")
      ->check(CLI::PositiveNumber);
  compare->add_option("--downsample", compare_downsample, "box-filter N x N blocks of both first")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? exit_ok : exit_usage;
  }

  if (info->parsed()) return run_info(scene_path, as_json, info_max_edge);
  if (compare->parsed()) return run_compare(compare_test, compare_reference, compare_downsample, compare_bright);
  if (view->parsed()) {
    scene s;
    if (!load_for_command(commands[0].scene, &commands[0].camera, s)) return exit_input_error;
    return run_viewer(s, commands[0].solver, view_extra);
  }
  if (render->parsed()) {
    scene s;
    if (!load_for_command(commands[1].scene, &commands[1].camera, s)) return exit_input_error;
    return run_render(s, commands[1].solver, render_extra);
  }
  if (commands[2].app->parsed()) {
    scene s;
    if (!load_for_command(commands[2].scene, &commands[2].camera, s)) return exit_input_error;
    return run_trace(s, commands[2].solver, trace_extra);
  }
  if (commands[3].app->parsed()) {
    scene s;
    if (!load_for_command(commands[3].scene, &commands[3].camera, s)) return exit_input_error;
    return run_solve(s, commands[3].solver, solve_extra);
  }
  if (bench->parsed()) return run_bench_command(bench_extra);

  // No subcommand: the main job on the embedded Cornell box: the window
  // when there is a display, otherwise a headless render to bounce.png in
  // the current folder.
  scene s;
  if (!load_for_command("", nullptr, s)) return exit_input_error;
  const char* display = std::getenv("DISPLAY");
  if (display && *display) return run_viewer(s, solver_settings{}, viewer_options{});
  std::cout << "bounce: no display; rendering headless\n";
  return run_render(s, solver_settings{}, render_options{});
}

}  // namespace bounce
