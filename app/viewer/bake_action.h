// The panel's "Bake to file": the solution the window shows, on the mesh it
// belongs to, written for other tools (radiosity/bake.h) at the window's
// exposure, so the colours in Blender or three.js are the ones on screen
// (with the filmic curve off).
#pragma once

#include <string>

#include "viewer/solver_worker.h"

namespace bounce {

// Writes `path` (its extension names the format; empty: a new .glb named
// after the scene, dated_file_name). Returns the panel's message: where it
// went, or why it did not.
std::string bake_shown_solution(const worker_view& view, std::string path, double exposure);

}  // namespace bounce
