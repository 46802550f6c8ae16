#include "cli/cli.h"

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>
#include <type_traits>
#include <vector>

#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "bench/bench_command.h"
#include "cli/bake_command.h"
#include "cli/compare_command.h"
#include "cli/console.h"
#include "cli/info_command.h"
#include "cli/render_command.h"
#include "cli/scene_argument.h"
#include "cli/solve_command.h"
#include "cli/trace_command.h"
#include "cli/view_command.h"
#include "common/exit_code.h"

namespace bounce {
namespace {

// The options of the whole command, before or after the subcommand.
struct program_options {
  bool quiet = false;
  int threads = 0;    // 0: one per core
  std::string scene;  // with no command: the scene to open
};

void add_program_options(CLI::App& app, program_options& options) {
  app.require_subcommand(0, 1);
  // Options of the whole command may also follow the subcommand (`bounce render --quiet`).
  app.fallthrough();
  app.set_version_flag("--version", std::string("bounce ") + BOUNCE_VERSION);
  app.add_flag("--quiet,-q", options.quiet, "print only warnings and errors: no progress bars, no reports");
  app.add_option("--threads", options.threads, "worker threads (default: one per core)")->check(CLI::Range(1, 4096));
  app.add_option("SCENE", options.scene,
                 "with no command: open this scene as `bounce view SCENE` does (headless: render it to bounce.png)")
      ->check(named_scene());
}

// A subcommand: its name and help line, and its options' functions bound
// to where the options are kept. `check` may be empty: nothing to check.
struct subcommand {
  const char* name;
  const char* description;
  std::function<void(CLI::App&)> add;
  std::function<std::string(const CLI::App&)> check;  // an error message (a usage error), or empty
  std::function<int()> run;
};

template <typename options_type>
subcommand bind_command(const char* name, const char* description, options_type& options,
                        void (*add)(CLI::App&, options_type&),
                        std::string (*check)(const CLI::App&, std::type_identity_t<options_type>&),
                        int (*run)(const std::type_identity_t<options_type>&)) {
  subcommand c{name, description, [&options, add](CLI::App& app) { add(app, options); }, nullptr,
               [&options, run] { return run(options); }};
  if (check) c.check = [&options, check](const CLI::App& app) { return check(app, options); };
  return c;
}

// With no command, SCENE is a scene file: a word that is neither is a
// mistyped command, and SCENE beside a command is one argument too many.
std::string check_program_scene(const std::string& scene, bool any_command) {
  if (any_command && !scene.empty()) return "unexpected argument '" + scene + "'";
  if (!scene.empty() && !scene.starts_with("generated:") && !std::filesystem::path(scene).has_extension() &&
      !std::filesystem::exists(scene))
    return "'" + scene +
           "' is neither a command nor a scene file (commands: info, view, render, "
           "trace, solve, bake, bench, compare)";
  return {};
}

// No subcommand: the main job, on the scene named or the embedded Cornell
// box: the window when there is a display, otherwise a headless render to
// bounce.png in the current folder.
int run_without_command(const std::string& path) {
  scene s;
  if (int code = load_for_command(path, nullptr, s); code != exit_ok) return code;
  const char* display = std::getenv("DISPLAY");
  if (display && *display) return run_viewer(s, solver_settings{}, viewer_options{});
  say("bounce: no display; rendering headless\n");
  return render_scene(s, render_options{});
}

}  // namespace

int run_cli(int argc, char** argv) {
  CLI::App app{
      "Bounce: global illumination. Hierarchical radiosity with a live Gouraud view, two-pass ray-traced stills\n"
      "and a path-traced reference.\n"
      "SCENE is a .json scene, a bare .obj, a glTF 2.0 .gltf or .glb, a .ply, .stl, .dae, .fbx, .3ds or .off model, or "
      "generated:NAME for a procedural scene\n"
      "(generated:box-room-60, generated:interior-10k to generated:interior-20m); without one, the embedded\n"
      "Cornell box."};
  program_options program;
  add_program_options(app, program);

  info_options info;
  view_options view;
  render_options render;
  trace_options trace;
  solve_options solve;
  solve_options bake;
  bench_options bench;
  compare_options compare;
  // In the order `bounce --help` lists them.
  const subcommand commands[] = {
      bind_command("info", "load and validate a scene, print its counts", info, add_info_options, nullptr, run_info),
      bind_command("view", "open the interactive window", view, add_view_options, check_view_options, run_view),
      bind_command("render", "solve and render the Gouraud view headlessly to a picture file", render,
                   add_render_options, check_render_options, run_render),
      bind_command("trace", "solve, then ray trace a still (two-pass), or path trace a reference", trace,
                   add_trace_options, check_trace_options, run_trace),
      bind_command("solve", "run the radiosity solver and report statistics", solve, add_solve_options,
                   check_solve_options, run_solve),
      bind_command("bake", "solve, then write the meshes with their light as glTF, PLY or OBJ for other tools", bake,
                   add_bake_options, check_bake_options, run_solve),
      bind_command("bench", "measure speed against error: every method on every bench scene", bench, add_bench_options,
                   nullptr, run_bench_command),
      bind_command("compare", "error of one PFM picture against a reference PFM", compare, add_compare_options, nullptr,
                   run_compare),
  };
  std::vector<CLI::App*> subcommands;
  for (const subcommand& c : commands) {
    subcommands.push_back(app.add_subcommand(c.name, c.description));
    c.add(*subcommands.back());
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? exit_ok : exit_usage;
  }
  auto usage_error = [](const std::string& message) {
    std::cerr << "error: " << message << "\n";
    return exit_usage;
  };
  // At most one subcommand is parsed (require_subcommand(0, 1)).
  const subcommand* chosen = nullptr;
  for (std::size_t i = 0; i < subcommands.size(); ++i)
    if (subcommands[i]->parsed()) {
      chosen = &commands[i];
      // Combinations in which an option would be accepted and then
      // ignored, and output files, are refused before any long work starts.
      if (chosen->check)
        if (std::string e = chosen->check(*subcommands[i]); !e.empty()) return usage_error(e);
    }

  set_quiet(program.quiet);
  std::optional<tbb::global_control> thread_limit;
  if (program.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(program.threads));

  if (std::string e = check_program_scene(program.scene, chosen != nullptr); !e.empty()) return usage_error(e);
  return chosen ? chosen->run() : run_without_command(program.scene);
}

}  // namespace bounce
