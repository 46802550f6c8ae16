#include "cli.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <tuple>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "bench_command.h"
#include "compare_command.h"
#include "console.h"
#include "image/picture_file.h"
#include "info_command.h"
#include "render_command.h"
#include "scene/camera_file.h"
#include "scene/reader_support.h"
#include "scene/scene_io.h"
#include "scene/scene_validate.h"
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

std::string format_g(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

}  // namespace

// CLI11's PositiveNumber and Range let NaN and infinities through and print
// DBL_MAX in full (309 digits); this prints limits with %g.

CLI::Validator number_in(double lo, double hi, bool lo_open, bool hi_open) {
  const bool unbounded = std::isinf(hi);
  const std::string range =
      unbounded ? std::string(lo_open ? "> " : ">= ") + format_g(lo)
                : std::string(lo_open ? "(" : "[") + format_g(lo) + ", " + format_g(hi) + (hi_open ? ")" : "]");
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double v = 0.0;
        if (!parse_double(text, v)) return "'" + text + "' is not a finite number";
        if (v < lo || (lo_open && v == lo) || v > hi || (hi_open && v == hi))
          return format_g(v) + " is out of range: must be " + (unbounded ? range : "in " + range);
        return {};
      },
      unbounded ? range : "in " + range);
}

namespace {

// A count: digits only (CLI11 reads "-1" into an unsigned as 2^64 - 1), at most `most`.
CLI::Validator count_at_most(std::uint64_t most) {
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        std::string_view digits = text;
        if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
        std::uint64_t v = 0;
        auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
        if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size())
          return "'" + text + "' is not a whole number from 0 to " + std::to_string(most);
        if (v > most) return text + " is out of range: must be at most " + std::to_string(most);
        return {};
      },
      most == std::numeric_limits<std::uint64_t>::max() ? ">= 0" : "0 to " + std::to_string(most));
}

// --eye, --target, --up: three finite numbers, each at most the scene
// files' limit in magnitude.
const CLI::Validator vec3_check(
    [](std::string& text) -> std::string {
      const auto v = parse_vec3(text);
      if (!v) return "expected x,y,z (three finite numbers), got '" + text + "'";
      for (int i = 0; i < 3; ++i)
        if (std::abs((*v)[i]) > max_file_number)
          return "coordinate " + format_g((*v)[i]) + " is out of range (limit " + format_g(max_file_number) +
                 " in magnitude)";
      return {};
    },
    "x,y,z");

const CLI::Validator size_check(
    [](std::string& text) -> std::string {
      const auto size = parse_size(text);
      if (!size) return "expected WxH (two whole numbers), got '" + text + "'";
      return check_image_size(size->first, size->second);
    },
    "WxH");

void print_warnings(const load_report& report) {
  for (const std::string& w : report.warnings) std::cerr << "warning: " << w << "\n";
  if (report.dropped_faces) std::cerr << "warning: " << report.dropped_faces << " degenerate face(s) dropped\n";
}

}  // namespace

// Loads the scene named on the command line (or the embedded default) and
// applies the camera overrides. Prints the error and returns its exit code
// (exit_ok on success): a scene that cannot be used is an input error, an
// override that makes the camera invalid a usage error.
int load_for_command(const std::string& path, const camera_options* camera_overrides, scene& s) {
  load_report report;
  if (!load_scene(path.empty() ? default_scene_path : path, s, report)) {
    print_warnings(report);  // what was said before the failure often explains it
    std::cerr << "error: " << report.error << "\n";
    return exit_input_error;
  }
  print_warnings(report);
  if (camera_overrides) {
    // A camera file is a file that may be unusable (exit 1); the options
    // typed over it are the command line (exit 2).
    if (std::string e; !camera_overrides->file.empty() && !load_camera_file(camera_overrides->file, s.view, e)) {
      std::cerr << "error: --camera: " << e << "\n";
      return exit_input_error;
    }
    if (std::string e = apply_camera_options(*camera_overrides, s.view); !e.empty()) {
      std::cerr << "error: " << e << "\n";
      return exit_usage;
    }
    // The scene file's size, when --size did not replace it: the same limits.
    if (std::string e = check_image_size(s.view.width, s.view.height); !e.empty()) {
      std::cerr << "error: " << s.source << ": camera.size: " << e << " (use --size)\n";
      return exit_input_error;
    }
  }
  return exit_ok;
}

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

std::string check_image_size(long long width, long long height) {
  if (width < 1 || height < 1 || width > max_image_side || height > max_image_side)
    return "size " + std::to_string(width) + "x" + std::to_string(height) + " must be from 1 to " +
           std::to_string(max_image_side) + " pixels per side";
  if (width * height > max_image_pixels)
    return "size " + std::to_string(width) + "x" + std::to_string(height) + " has " + std::to_string(width * height) +
           " pixels, more than the limit of " + std::to_string(max_image_pixels) + " (" +
           std::to_string(max_image_side) + "x" + std::to_string(max_image_pixels / max_image_side) + ")";
  return {};
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
  std::map<std::string, solver_method> solvers;
  for (const auto& m : solver_method_names()) solvers.emplace(std::string(m.name), m.method);
  command.add_option("--solver", o.method, "radiosity solver")
      ->transform(CLI::CheckedTransformer(solvers, CLI::ignore_case))
      ->default_str(std::string(name_of(o.method)));
  command
      .add_option("--link-tolerance", o.link_tolerance,
                  "hierarchical: power a link may carry unrefined, a fraction of the power leaving all surfaces")
      ->check(number_in(0.0, 1.0, true))
      ->capture_default_str();
  command
      .add_option("--mirror-depth", o.form_factors.mirror_depth,
                  "planar mirrors a transfer may pass, one after another (hierarchical: links through chains "
                  "of them; progressive: mirror images); 0: planar mirrors are traced like curved ones")
      ->check(CLI::Range(0, max_mirror_depth))
      ->capture_default_str();
  std::map<std::string, form_factor_method> methods;
  for (const auto& m : form_factor_method_names()) methods.emplace(std::string(m.name), m.method);
  command.add_option("--method", o.form_factors.method, "form-factor method")
      ->transform(CLI::CheckedTransformer(methods, CLI::ignore_case))
      ->default_str(std::string(name_of(o.form_factors.method)));
  command
      .add_option("--max-edge", o.max_edge,
                  "longest element edge, scene units (default: diagonal/10, split while solving; progressive: /24)")
      ->check(number_in(0.0, INFINITY, true));
  command.add_option("--until", o.stop.unshot_fraction, "stop when the unshot power fraction falls below this")
      ->check(number_in(0.0, 1.0))
      ->capture_default_str();
  command.add_option("--max-shots", o.stop.max_shots, "stop after this many shots (0: no limit)")
      ->check(count_at_most(std::numeric_limits<std::uint64_t>::max()));
  command.add_option("--time", o.stop.seconds, "stop after this many seconds of solving (0: no limit)")
      ->check(number_in(0.0, INFINITY));
  command
      .add_option("--patch-edge", o.patch_edge,
                  "size of the shooting patches over the elements (substructuring); default 4 x max edge, "
                  "0: every element shoots (exact)")
      ->check(number_in(0.0, INFINITY));
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
  CLI::Option* adaptive =
      command.add_flag("--adaptive", o.adaptive.enabled,
                       "adaptive meshing: refine at contacts and near emitters, then where the radiosity changes "
                       "and along shadow edges while solving");
  command
      .add_option("--tolerance", o.adaptive.tolerance,
                  "adaptive: split where vertex radiosities differ by this fraction")
      ->check(number_in(0.0, INFINITY, true))
      ->capture_default_str()
      ->needs(adaptive);
  command
      .add_option("--min-edge", o.adaptive.min_edge,
                  "hierarchical and --adaptive: elements whose longest edge is at most this are not split "
                  "(default: max edge / 8)")
      ->check(number_in(0.0, INFINITY, true));
}

std::span<const char* const> solver_option_names() {
  static constexpr const char* names[] = {"--solver",     "--link-tolerance", "--mirror-depth", "--method",
                                          "--max-edge",   "--until",          "--max-shots",    "--time",
                                          "--patch-edge", "--full-rays",      "--rays",         "--hemicube",
                                          "--adaptive",   "--tolerance",      "--min-edge"};
  return names;
}

std::string given_options(const CLI::App& command, std::span<const char* const> names) {
  std::string list;
  for (const char* name : names)
    if (command.count(name) > 0) list += std::string(list.empty() ? "" : ", ") + name;
  return list;
}

std::string check_solver_options(const CLI::App& command, solver_settings& settings) {
  // Options of the progressive solver choose it, unless the hierarchical
  // one was asked for by name: then they would be ignored.
  static constexpr const char* progressive_only[] = {"--method",   "--patch-edge", "--full-rays", "--rays",
                                                     "--hemicube", "--adaptive",   "--tolerance"};
  if (const std::string given = given_options(command, progressive_only); !given.empty()) {
    if (command.count("--solver") && settings.method == solver_method::hierarchical)
      return given + (given.find(',') == std::string::npos ? " applies" : " apply") + " to --solver progressive only";
    settings.method = solver_method::progressive;
  }
  if (settings.method != solver_method::hierarchical && command.count("--link-tolerance"))
    return "--link-tolerance applies to --solver hierarchical only";
  if (settings.method == solver_method::progressive && !settings.adaptive.enabled && command.count("--min-edge"))
    return "--min-edge applies to --solver hierarchical or --adaptive only";
  const bool hemicube = settings.form_factors.method == form_factor_method::hemicube;
  if (hemicube && command.count("--rays")) return "--rays applies to --method raycast only";
  if (hemicube && command.count("--full-rays")) return "--full-rays applies to --method raycast only";
  if (!hemicube && command.count("--hemicube")) return "--hemicube applies to --method hemicube only";
  return {};
}

void add_camera_options(CLI::App& command, camera_options& o) {
  command.add_option("--camera", o.file,
                     "camera file ({\"camera\": {...}} as in a scene file, e.g. saved from the window's panel); "
                     "--eye, --target, --up, --fov and --size override it");
  command.add_option("--eye", o.eye, "camera position x,y,z")->check(vec3_check);
  command.add_option("--target", o.target, "point looked at x,y,z")->check(vec3_check);
  command.add_option("--up", o.up, "up direction x,y,z")->check(vec3_check);
  command.add_option("--fov", o.fov, "vertical field of view, degrees")->check(number_in(0.0, 180.0, true, true));
  command
      .add_option("--size", o.size,
                  "image size WxH (1 to " + std::to_string(max_image_side) + " per side, at most " +
                      std::to_string(max_image_pixels) + " pixels)")
      ->check(size_check);
}

int run_cli(int argc, char** argv) {
  CLI::App app{
      "Bounce: global illumination. Hierarchical radiosity with a live Gouraud view, two-pass ray-traced stills\n"
      "and a path-traced reference.\n"
      "SCENE is a .json scene, a bare .obj, a glTF 2.0 .gltf or .glb, or generated:NAME for a procedural scene\n"
      "(generated:box-room-60, generated:interior-10k to generated:interior-20m); without one, the embedded\n"
      "Cornell box."};
  app.require_subcommand(0, 1);
  // Options of the whole command may also follow the subcommand (`bounce render --quiet`).
  app.fallthrough();
  app.set_version_flag("--version", std::string("bounce ") + BOUNCE_VERSION);
  bool quiet_flag = false;
  app.add_flag("--quiet,-q", quiet_flag, "print only warnings and errors: no progress bars, no reports");
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (default: one per core)")->check(CLI::Range(1, 4096));
  std::string short_scene;
  app.add_option("SCENE", short_scene,
                 "with no command: open this scene as `bounce view SCENE` does (headless: render it to bounce.png)");

  std::string scene_path;
  bool as_json = false;
  double info_max_edge = 0.0;
  CLI::App* info = app.add_subcommand("info", "load and validate a scene, print its counts");
  info->add_option("SCENE", scene_path,
                   "scene file (.json, .obj, .gltf or .glb), or generated:NAME (e.g. generated:interior-1m)");
  info->add_flag("--json", as_json, "machine-readable output");
  info->add_option("--max-edge", info_max_edge, "tessellation size for curved surfaces")
      ->check(number_in(0.0, INFINITY, true));

  struct solving_command {
    const char* name;
    const char* help;
    bool has_camera;  // solve renders nothing: no camera options
    CLI::App* app = nullptr;
    std::string scene;
    solver_settings solver;
    camera_options camera;
  };
  solving_command commands[] = {
      {"view", "open the interactive window", true, nullptr, {}, {}, {}},
      {"render", "solve and render the Gouraud view headlessly to a picture file", true, nullptr, {}, {}, {}},
      {"trace", "solve, then ray trace a still (two-pass), or path trace a reference", true, nullptr, {}, {}, {}},
      {"solve", "run the radiosity solver and report statistics", false, nullptr, {}, {}, {}},
  };
  for (solving_command& c : commands) {
    c.app = app.add_subcommand(c.name, c.help);
    c.app->add_option("SCENE", c.scene,
                      "scene file (.json, .obj, .gltf or .glb), or generated:NAME (e.g. generated:interior-1m)");
    add_solver_options(*c.app, c.solver);
    if (c.has_camera) add_camera_options(*c.app, c.camera);
  }
  render_options render_extra;
  CLI::App* render = commands[1].app;
  render
      ->add_option("--out", render_extra.out_path,
                   "picture of the Gouraud view; the extension picks the format: .png (tone-mapped), or .pfm, .exr, "
                   ".hdr (linear radiance, unscaled)")
      ->capture_default_str();
  render->add_option("--pfm", render_extra.pfm_path, "also write the view in linear radiance to this PFM");
  CLI::Option* render_frames = render->add_option(
      "--frames", render_extra.frames_dir,
      "also write PNG frames of the convergence into DIR: after 1, 2, 4, 8, ... shots and at the end");
  render
      ->add_option("--frame-every", render_extra.frame_every,
                   "with --frames: a frame every N shots instead of at doubling counts")
      ->check(CLI::Range(1L, 1L << 40))
      ->needs(render_frames);
  render->add_option("--exposure", render_extra.exposure, "displayed value = radiance x exposure")
      ->check(number_in(min_exposure, max_exposure))
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
  render
      ->add_option("--msaa", render_extra.msaa,
                   "antialiasing samples per pixel; 0 draws as the window does on software GL")
      ->check(CLI::IsMember({0, 1, 2, 4, 8}))
      ->capture_default_str();
  viewer_options view_extra;
  CLI::App* view = commands[0].app;
  CLI::Option* view_frames = view->add_option("--frames", view_extra.frames, "scripted run: draw this many frames")
                                 ->check(CLI::Range(1, 1 << 30));
  view->add_option("--screenshot", view_extra.screenshot_path,
                   "with --frames: after the scripted frames, save the window as PNG")
      ->needs(view_frames);
  view->add_option(
          "--still", view_extra.still_path,
          "with --frames: ray trace a still at --size halfway through (as the panel's button does), save it as PNG")
      ->needs(view_frames);
  view->add_flag("--error-plot", view_extra.error_plot,
                 "path trace a 64x64 reference of the camera at the start and plot the error against it");
  view->add_flag("--exit", view_extra.exit_after, "with --frames: quit after the scripted frames")->needs(view_frames);
  CLI::Option* view_shots = view->add_option("--screenshots", view_extra.screenshots_dir,
                                             "with --frames: save the view (without the panel) at frame 1 and every "
                                             "--screenshot-every frames into DIR")
                                ->check(CLI::ExistingDirectory)
                                ->needs(view_frames);
  view->add_option("--screenshot-every", view_extra.screenshot_every, "with --screenshots: frames between screenshots")
      ->check(CLI::Range(1, 1 << 30))
      ->needs(view_shots);
  view->add_option("--refined-passes", view_extra.refined_passes,
                   "with --frames: the last frame waits until refinement at rest shows this many passes")
      ->check(CLI::Range(1, 64))
      ->needs(view_frames);
  view->add_flag("--no-panel-in-screenshot{false}", view_extra.screenshot_panel,
                 "with --screenshot: save the view without the panel")
      ->needs(view_frames);
  view->add_flag("--no-refine-at-rest{false}", view_extra.refine_at_rest,
                 "keep the live Gouraud view while the camera rests (the panel's \"refine at rest\" off)");
  view->add_flag("--paused", view_extra.start_paused, "mesh and show the scene but start the solver paused");
  view->add_option("--msaa", view_extra.msaa, "window antialiasing samples (default: 4 on a GPU, 0 on software GL)")
      ->check(CLI::Range(0, 16));
  trace_options trace_extra;
  CLI::App* trace = commands[2].app;
  add_trace_options(*trace, trace_extra);
  trace->add_option("--stats", trace_extra.stats_path,
                    "write trace statistics (and the radiosity pass's) as JSON to this file");
  solve_options solve_extra;
  CLI::App* solve = commands[3].app;
  solve->add_option("--ply", solve_extra.ply_path, "write the patch mesh with per-vertex radiosity as PLY");
  solve->add_option("--stats", solve_extra.stats_path, "write solver statistics as JSON to this file");
  solve->add_flag("--reference", solve_extra.reference,
                  "also solve the full matrix (small scenes) and report the difference");
  solve->add_flag("--ray-baseline", solve_extra.ray_baseline,
                  "raycast: replay 2M of the solver's shadow rays through Embree's rtcOccluded1 and compare rates");
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
      ->check(number_in(0.0, INFINITY, true));
  compare->add_option("--downsample", compare_downsample, "box-filter N x N blocks of both first (N at most the size)")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? exit_ok : exit_usage;
  }

  // Combinations in which an option would be accepted and then ignored.
  auto usage_error = [](const std::string& message) {
    std::cerr << "error: " << message << "\n";
    return exit_usage;
  };
  for (solving_command& c : commands)
    if (c.app->parsed())
      if (std::string e = check_solver_options(*c.app, c.solver); !e.empty()) return usage_error(e);
  if (trace->parsed())
    if (std::string e = check_trace_options(*trace, trace_extra); !e.empty()) return usage_error(e);
  if (solve->parsed() && (solve_extra.reference || solve_extra.ray_baseline)) {
    // Both measure the progressive solver (against the matrix solution of
    // its own system, or Embree's raw rate on its rays).
    const std::string option = solve_extra.reference ? "--reference" : "--ray-baseline";
    if (solve->count("--solver") && commands[3].solver.method == solver_method::hierarchical)
      return usage_error(option + " applies to --solver progressive only");
    if (solve->count("--link-tolerance"))
      return usage_error("--link-tolerance applies to --solver hierarchical only (" + option +
                         " measures the progressive solver)");
    commands[3].solver.method = solver_method::progressive;
  }
  if (solve->parsed() && solve_extra.ray_baseline &&
      commands[3].solver.form_factors.method != form_factor_method::raycast)
    return usage_error("--ray-baseline applies to --method raycast only (the hemicube casts no shadow rays)");

  set_quiet(quiet_flag);
  std::optional<tbb::global_control> thread_limit;
  if (threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));

  // Output files are checked before any long work starts.
  std::vector<std::tuple<const char*, std::string, bool>> outputs;  // option, path, must be a picture
  if (render->parsed()) {
    outputs = {{"--out", render_extra.out_path, true},
               {"--pfm", render_extra.pfm_path, false},
               {"--stats", render_extra.stats_path, false}};
    const bool linear = is_linear(picture_format_of(render_extra.out_path).value_or(picture_format::png));
    if (linear)
      for (const char* png_only : {"--panel", "--tone", "--exposure"})
        if (render->count(png_only))
          return usage_error(std::string(png_only) + " applies to PNG output only (--out " + render_extra.out_path +
                             " is linear radiance)");
    if (!render_extra.frames_dir.empty()) {
      namespace fs = std::filesystem;
      const fs::path parent = fs::absolute(render_extra.frames_dir).parent_path();
      std::error_code ec;
      if (!fs::is_directory(render_extra.frames_dir, ec) && !fs::is_directory(parent, ec))
        return usage_error("--frames " + render_extra.frames_dir + ": the folder " + parent.string() +
                           " does not exist");
    }
  }
  if (trace->parsed()) {
    outputs = {{"--out", trace_extra.out_path, true},
               {"--pfm", trace_extra.pfm_path, false},
               {"--stats", trace_extra.stats_path, false}};
    if (is_linear(picture_format_of(trace_extra.out_path).value_or(picture_format::png)) && trace->count("--exposure"))
      return usage_error("--exposure applies to PNG output only (--out " + trace_extra.out_path +
                         " is linear radiance)");
  }
  if (solve->parsed()) outputs = {{"--ply", solve_extra.ply_path, false}, {"--stats", solve_extra.stats_path, false}};
  if (view->parsed())
    outputs = {{"--screenshot", view_extra.screenshot_path, false}, {"--still", view_extra.still_path, false}};
  for (const auto& [option, path, picture] : outputs)
    if (!path.empty())
      if (std::string e = check_output_path(option, path, picture); !e.empty()) return usage_error(e);

  const bool any_command =
      std::any_of(std::begin(commands), std::end(commands), [](const solving_command& c) { return c.app->parsed(); }) ||
      info->parsed() || compare->parsed() || bench->parsed();
  if (any_command && !short_scene.empty()) return usage_error("unexpected argument '" + short_scene + "'");
  if (!short_scene.empty() && !short_scene.starts_with("generated:") &&
      !std::filesystem::path(short_scene).has_extension() && !std::filesystem::exists(short_scene))
    return usage_error("'" + short_scene +
                       "' is neither a command nor a scene file (commands: info, view, render, "
                       "trace, solve, bench, compare)");

  if (info->parsed()) return run_info(scene_path, as_json, info_max_edge);
  if (compare->parsed()) return run_compare(compare_test, compare_reference, compare_downsample, compare_bright);
  for (solving_command& c : commands) {
    if (!c.app->parsed()) continue;
    scene s;
    if (int code = load_for_command(c.scene, c.has_camera ? &c.camera : nullptr, s); code != exit_ok) return code;
    if (c.app == view) return run_viewer(s, c.solver, view_extra);
    if (c.app == render) return run_render(s, c.solver, render_extra);
    if (c.app == trace) return run_trace(s, c.solver, trace_extra);
    return run_solve(s, c.solver, solve_extra);
  }
  if (bench->parsed()) return run_bench_command(bench_extra);

  // No subcommand: the main job, on the scene named or the embedded
  // Cornell box: the window when there is a display, otherwise a headless
  // render to bounce.png in the current folder.
  scene s;
  if (int code = load_for_command(short_scene, nullptr, s); code != exit_ok) return code;
  const char* display = std::getenv("DISPLAY");
  if (display && *display) return run_viewer(s, solver_settings{}, viewer_options{});
  say("bounce: no display; rendering headless\n");
  return run_render(s, solver_settings{}, render_options{});
}

}  // namespace bounce
