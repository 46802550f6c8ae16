// Draco-compressed glTF geometry (KHR_draco_mesh_compression), decoded with
// Debian's libdraco: the triangles and the attributes asked for by their
// Draco ids, which the extension maps to glTF's attribute names.
#pragma once

#include <array>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace bounce {

struct draco_mesh {
  std::size_t points = 0;                       // vertices
  std::vector<std::array<int, 3>> triangles;    // indices into the points
  std::map<int, std::vector<double>> attributes;  // Draco id -> points x components values (dequantised)
};

// Decodes the mesh in `bytes` with the attributes `wanted` (Draco id ->
// components per point). Returns an empty string, or what went wrong (a
// point cloud, an attribute missing or with fewer components, a corrupt
// stream).
std::string decode_draco_mesh(std::string_view bytes, const std::map<int, int>& wanted, draco_mesh& out);

}  // namespace bounce
