// The solved light written out with the mesh it was solved on, for other
// tools: glTF (.glb, .gltf) with per-vertex colours under unlit materials,
// PLY with colours, and OBJ with per-vertex colours. `bounce bake` and the
// window's "Bake to file" write these; docs/bake.md says what each holds.
#pragma once

#include <optional>
#include <string>

#include "radiosity/solution.h"
#include "scene/scene.h"

namespace bounce {

enum class bake_format { glb, gltf, ply, obj };

// The format a path's extension names (case-insensitive), if any.
std::optional<bake_format> bake_format_of(const std::string& path);

struct bake_settings {
  double exposure = 0.0;  // <= 0: automatic (the reflecting vertices' 95th percentile at 0.8)
  bool parts = false;     // glTF: also _DIRECT and _INDIRECT
};

// The exposure a bake uses: the settings', or the automatic one.
double bake_exposure(const patch_mesh& mesh, const radiosity_snapshot& solution, const bake_settings& settings);

// The colour a vertex is baked with: its radiance B / pi times the
// exposure, clamped to [0, 1], linear (glTF's COLOR_0; a viewer encodes it
// to sRGB for the screen, as Bounce's pictures do).
rgb baked_colour(const rgb& radiosity, double exposure);

// Writes the mesh (`mesh`, the one `solution` is on; the surfaces named
// after `s`'s) with its light to `path`, in the format its extension
// names, whole or not at all (a file beside it, then renamed). Returns
// false with `error` naming the file. `exposure_used`, if given, gets the
// exposure.
bool write_bake(const std::string& path, const scene& s, const patch_mesh& mesh, const radiosity_snapshot& solution,
                const bake_settings& settings, std::string& error, double* exposure_used = nullptr);

}  // namespace bounce
