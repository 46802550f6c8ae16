// `bounce bake`: solve, then write the meshes with the solved light for
// other tools (radiosity/bake.h: glTF vertex colours, PLY, OBJ).
#pragma once

#include <string>

#include "cli/solve_command.h"

namespace CLI {
class App;
}  // namespace CLI

namespace bounce {

void add_bake_options(CLI::App& command, solve_options& options);

// The solver options as for solve, and --out: a .glb, .gltf, .ply or .obj
// path that can be written; an error message or an empty string.
std::string check_bake_options(const CLI::App& command, solve_options& options);

}  // namespace bounce
