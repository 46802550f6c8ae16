#include "cli/bake_command.h"

#include <CLI/CLI.hpp>

#include "cli/option_values.h"
#include "cli/scene_argument.h"
#include "cli/solver_options.h"

namespace bounce {

void add_bake_options(CLI::App& command, solve_options& options) {
  add_scene_argument(command, options.scene);
  add_solver_options(command, options.solver);
  command
      .add_option("--out", options.bake_path,
                  "file to write: .glb or .gltf (COLOR_0 under KHR_materials_unlit), .ply or .obj (vertex colours)")
      ->required();
  command.add_option("--exposure", options.bake.exposure,
                     "scale on radiance before the colours clamp to [0, 1] (default: automatic, as the PLY)");
  command.add_flag("--parts", options.bake.parts,
                   "glTF: also the direct and indirect light, as attributes _DIRECT and _INDIRECT");
  command.add_option("--stats", options.stats_path, "write solver statistics as JSON to this file");
}

std::string check_bake_options(const CLI::App& command, solve_options& options) {
  if (std::string e = check_solver_options(command, options.solver); !e.empty()) return e;
  const std::optional<bake_format> format = bake_format_of(options.bake_path);
  if (!format) return "--out: expected a .glb, .gltf, .ply or .obj file, got '" + options.bake_path + "'";
  if (command.count("--exposure") && !(options.bake.exposure > 0.0)) return "--exposure: must be above 0";
  if (options.bake.parts && *format != bake_format::glb && *format != bake_format::gltf)
    return "--parts applies to glTF output only (.glb, .gltf)";
  return check_output_files({{"--out", options.bake_path, false}, {"--stats", options.stats_path, false}});
}

}  // namespace bounce
