#include "radiosity/bake.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

// Debian's libtinygltf.so holds the implementation.
#include <tiny_gltf.h>

#include "base/whole_file.h"
#include "image/tonemap.h"
#include "mesh/ply.h"

namespace bounce {

namespace {

namespace fs = std::filesystem;

bool ends_with_icase(const std::string& s, const std::string& end) {
  if (s.size() < end.size()) return false;
  return std::equal(end.begin(), end.end(), s.end() - std::ptrdiff_t(end.size()),
                    [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

// One surface's part of the mesh: its vertices (renumbered) and elements.
struct surface_part {
  std::vector<std::uint32_t> vertices;  // mesh vertex of each local vertex
  std::vector<std::uint32_t> indices;   // local, three per element
};

std::vector<surface_part> parts_by_surface(const patch_mesh& mesh, std::size_t surfaces) {
  std::vector<surface_part> parts(surfaces);
  std::vector<std::int64_t> local(mesh.vertex_count(), -1);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const std::size_t s = std::size_t(mesh.element_surfaces[e]);
    if (s >= parts.size()) parts.resize(s + 1);
    for (int k = 0; k < 3; ++k) {
      const std::size_t v = std::size_t(mesh.elements[e][k]);
      if (local[v] < 0) {
        local[v] = std::int64_t(parts[s].vertices.size());
        parts[s].vertices.push_back(std::uint32_t(v));
      }
      parts[s].indices.push_back(std::uint32_t(local[v]));
    }
  }
  return parts;
}

std::string surface_name(const scene& s, std::size_t i) {
  if (i < s.surfaces.size() && !s.surfaces[i].name.empty())
    return s.surfaces[i].back_of >= 0 ? s.surfaces[i].name + " (back)" : s.surfaces[i].name;
  return "surface " + std::to_string(i);
}

// Appends `n` floats as a buffer view and accessor; returns the accessor.
int add_floats(tinygltf::Model& m, const std::vector<float>& values, int components, bool bounds) {
  tinygltf::Buffer& buffer = m.buffers[0];
  const std::size_t offset = buffer.data.size();
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  buffer.data.insert(buffer.data.end(), bytes, bytes + values.size() * sizeof(float));
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = values.size() * sizeof(float);
  view.target = TINYGLTF_TARGET_ARRAY_BUFFER;
  m.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = int(m.bufferViews.size()) - 1;
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.count = values.size() / std::size_t(components);
  a.type = components == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_SCALAR;
  if (bounds && a.count > 0) {  // glTF requires them on POSITION
    a.minValues.assign(std::size_t(components), 1e300);
    a.maxValues.assign(std::size_t(components), -1e300);
    for (std::size_t i = 0; i < values.size(); ++i) {
      const std::size_t c = i % std::size_t(components);
      a.minValues[c] = std::min(a.minValues[c], double(values[i]));
      a.maxValues[c] = std::max(a.maxValues[c], double(values[i]));
    }
  }
  m.accessors.push_back(a);
  return int(m.accessors.size()) - 1;
}

int add_indices(tinygltf::Model& m, const std::vector<std::uint32_t>& indices) {
  tinygltf::Buffer& buffer = m.buffers[0];
  const std::size_t offset = buffer.data.size();
  const auto* bytes = reinterpret_cast<const unsigned char*>(indices.data());
  buffer.data.insert(buffer.data.end(), bytes, bytes + indices.size() * sizeof(std::uint32_t));
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = indices.size() * sizeof(std::uint32_t);
  view.target = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
  m.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = int(m.bufferViews.size()) - 1;
  a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  a.count = indices.size();
  a.type = TINYGLTF_TYPE_SCALAR;
  m.accessors.push_back(a);
  return int(m.accessors.size()) - 1;
}

void push(std::vector<float>& out, const vec3& v) {
  out.push_back(float(v.x));
  out.push_back(float(v.y));
  out.push_back(float(v.z));
}

bool write_gltf(std::ostream& out, bool binary, const scene& s, const patch_mesh& mesh,
                const radiosity_snapshot& solution, const bake_settings& settings, double exposure) {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "Bounce (radiosity baked into COLOR_0)";
  m.extensionsUsed = {"KHR_materials_unlit"};
  m.buffers.resize(1);
  tinygltf::Material unlit;
  unlit.name = "baked light (unlit)";
  unlit.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
  unlit.pbrMetallicRoughness.metallicFactor = 0.0;
  unlit.pbrMetallicRoughness.roughnessFactor = 1.0;
  unlit.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
  m.materials.push_back(unlit);
  tinygltf::Scene root;
  const bool parts = settings.parts && solution.direct.size() == mesh.vertex_count();
  const std::vector<surface_part> by_surface = parts_by_surface(mesh, s.surfaces.size());
  for (std::size_t i = 0; i < by_surface.size(); ++i) {
    const surface_part& part = by_surface[i];
    if (part.indices.empty()) continue;
    std::vector<float> positions, normals, colours, direct, indirect;
    for (const std::uint32_t v : part.vertices) {
      push(positions, mesh.positions[v]);
      push(normals, mesh.normals[v]);
      push(colours, baked_colour(solution.radiosity[v], exposure));
      if (parts) {
        const double scale = exposure / std::numbers::pi;
        push(direct, solution.direct[v] * scale);
        push(indirect, (solution.radiosity[v] - solution.direct[v]) * scale);
      }
    }
    tinygltf::Primitive p;
    p.mode = TINYGLTF_MODE_TRIANGLES;
    p.material = 0;
    p.attributes["POSITION"] = add_floats(m, positions, 3, true);
    p.attributes["NORMAL"] = add_floats(m, normals, 3, false);
    p.attributes["COLOR_0"] = add_floats(m, colours, 3, false);
    if (parts) {
      p.attributes["_DIRECT"] = add_floats(m, direct, 3, false);
      p.attributes["_INDIRECT"] = add_floats(m, indirect, 3, false);
    }
    p.indices = add_indices(m, part.indices);
    tinygltf::Mesh gm;
    gm.name = surface_name(s, i);
    gm.primitives.push_back(p);
    m.meshes.push_back(gm);
    tinygltf::Node node;
    node.name = gm.name;
    node.mesh = int(m.meshes.size()) - 1;
    m.nodes.push_back(node);
    root.nodes.push_back(int(m.nodes.size()) - 1);
  }
  std::ostringstream exposure_text;
  exposure_text << exposure;
  root.name = "baked light, exposure " + exposure_text.str();
  m.scenes.push_back(root);
  m.defaultScene = 0;
  m.buffers[0].name = "baked";
  tinygltf::TinyGLTF writer;
  return writer.WriteGltfSceneToStream(&m, out, !binary, binary);
}

// OBJ with the common per-vertex colour extension "v x y z r g b" (MeshLab,
// Blender): colours as shown, sRGB-encoded in [0, 1].
bool write_obj(std::ostream& out, const scene& s, const patch_mesh& mesh, const radiosity_snapshot& solution,
               double exposure) {
  out << "# Bounce: radiosity baked into vertex colours (v x y z r g b: radiance B/pi x exposure " << exposure
      << ", sRGB)\n";
  const std::vector<surface_part> by_surface = parts_by_surface(mesh, s.surfaces.size());
  char line[256];
  std::size_t first = 1;
  for (std::size_t i = 0; i < by_surface.size(); ++i) {
    const surface_part& part = by_surface[i];
    if (part.indices.empty()) continue;
    out << "o " << surface_name(s, i) << "\n";
    for (const std::uint32_t v : part.vertices) {
      const vec3& p = mesh.positions[v];
      const rgb c = baked_colour(solution.radiosity[v], exposure);
      std::snprintf(line, sizeof line, "v %.9g %.9g %.9g %.6f %.6f %.6f\n", p.x, p.y, p.z, linear_to_srgb(c.r),
                    linear_to_srgb(c.g), linear_to_srgb(c.b));
      out << line;
    }
    for (const std::uint32_t v : part.vertices) {
      const vec3& n = mesh.normals[v];
      std::snprintf(line, sizeof line, "vn %.6g %.6g %.6g\n", n.x, n.y, n.z);
      out << line;
    }
    for (std::size_t t = 0; t < part.indices.size(); t += 3) {
      const std::size_t a = first + part.indices[t], b = first + part.indices[t + 1], c = first + part.indices[t + 2];
      out << "f " << a << "//" << a << " " << b << "//" << b << " " << c << "//" << c << "\n";
    }
    first += part.vertices.size();
  }
  return bool(out);
}

}  // namespace

std::optional<bake_format> bake_format_of(const std::string& path) {
  if (ends_with_icase(path, ".glb")) return bake_format::glb;
  if (ends_with_icase(path, ".gltf")) return bake_format::gltf;
  if (ends_with_icase(path, ".ply")) return bake_format::ply;
  if (ends_with_icase(path, ".obj")) return bake_format::obj;
  return std::nullopt;
}

double bake_exposure(const patch_mesh& mesh, const radiosity_snapshot& solution, const bake_settings& settings) {
  if (settings.exposure > 0.0) return settings.exposure;
  // The reflecting vertices: emitters would wash everything out.
  std::vector<rgb> reflected;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    if (mesh.vertex_emission[v] == rgb(0.0)) reflected.push_back(solution.radiosity[v] / std::numbers::pi);
  return auto_exposure(reflected);
}

rgb baked_colour(const rgb& radiosity, double exposure) {
  return glm::clamp(radiosity * (exposure / std::numbers::pi), rgb(0.0), rgb(1.0));
}

bool write_bake(const std::string& path, const scene& s, const patch_mesh& mesh, const radiosity_snapshot& solution,
                const bake_settings& settings, std::string& error, double* exposure_used) {
  const std::optional<bake_format> format = bake_format_of(path);
  if (!format) {
    error = path + ": unknown bake format (expected .glb, .gltf, .ply or .obj)";
    return false;
  }
  if (solution.radiosity.size() != mesh.vertex_count()) {
    error = path + ": the solution is not on this mesh";
    return false;
  }
  const double exposure = bake_exposure(mesh, solution, settings);
  if (exposure_used) *exposure_used = exposure;
  // Whole or not at all (base/whole_file.h).
  return write_whole(
      path,
      [&](const std::string& file, std::string& reason) {
        std::ostringstream out;
        bool ok = true;
        if (*format == bake_format::ply)
          write_ply(out, mesh, solution.radiosity, exposure);
        else if (*format == bake_format::obj)
          ok = write_obj(out, s, mesh, solution, exposure);
        else
          ok = write_gltf(out, *format == bake_format::glb, s, mesh, solution, settings, exposure);
        if (!ok) {
          reason = "cannot encode the file";
          return false;
        }
        return write_bytes(file, out.str(), reason);
      },
      error);
}

}  // namespace bounce
