#include "mesh/ply.h"

#include <cstdio>
#include <numbers>

#include "image/tonemap.h"

namespace bounce {

void write_ply(std::ostream& out, const patch_mesh& mesh, const std::vector<rgb>& radiosity, double exposure) {
  out << "ply\nformat ascii 1.0\ncomment Bounce radiosity: radiosity_* is B in W/m^2 per scene unit^2, unscaled\n"
      << "comment red/green/blue: radiance B/pi x exposure " << exposure << ", sRGB\n"
      << "element vertex " << mesh.vertex_count() << "\n"
      << "property float x\nproperty float y\nproperty float z\n"
      << "property float nx\nproperty float ny\nproperty float nz\n"
      << "property float radiosity_r\nproperty float radiosity_g\nproperty float radiosity_b\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      << "element face " << mesh.element_count() << "\nproperty list uchar int vertex_indices\nend_header\n";
  char line[512];
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const vec3& p = mesh.positions[v];
    const vec3& n = mesh.normals[v];
    const rgb& b = radiosity[v];
    const glm::u8vec3 c = to_srgb8(b / std::numbers::pi, exposure);
    std::snprintf(line, sizeof line, "%.9g %.9g %.9g %.6g %.6g %.6g %.9g %.9g %.9g %d %d %d\n", p.x, p.y, p.z, n.x, n.y,
                  n.z, b.r, b.g, b.b, c.r, c.g, c.b);
    out << line;
  }
  for (const glm::ivec3& t : mesh.elements) out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
}

}  // namespace bounce
