// The formats Bounce does not read itself (PLY, STL, Collada .dae, FBX,
// 3DS, OFF), through Debian's assimp. OBJ and glTF keep their own readers,
// which name the line or object of a problem and repair more. assimp's
// importer parses; this reader applies the node transforms, keeps polygons
// as polygons, maps each material the way the OBJ and glTF readers do
// (diffuse colour and its texture to rho, emission to ke, two-sided), and
// turns what assimp warns of into Bounce's warnings, naming the file.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scene/reader_support.h"  // load_error
#include "scene/scene.h"

namespace bounce {

// The extensions read through assimp, lower case with the dot.
inline constexpr std::string_view assimp_extensions[] = {".ply", ".stl", ".dae", ".fbx", ".3ds", ".off"};

// Whether `path` ends in one of them (any case).
bool read_through_assimp(const std::string& path);

struct assimp_read_result {
  std::vector<surface> surfaces;  // one polygon mesh per assimp mesh, its node transforms applied
  std::vector<std::string> warnings;
};

// Reads `path`. New materials and textures are appended to the lists and
// faces refer to them by index. Points and lines are dropped with a
// warning; so are what Bounce cannot use (cameras, lights, animation,
// vertex colours), one warning per kind. Throws load_error naming the file.
assimp_read_result read_assimp(const std::string& path, std::vector<material>& materials,
                               std::vector<texture>& textures);

}  // namespace bounce
