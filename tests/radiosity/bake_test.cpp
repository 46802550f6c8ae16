// Baked light (radiosity/bake.h) read back: the glTF's COLOR_0 under an
// unlit material, its _DIRECT and _INDIRECT, the OBJ's and the PLY's
// vertex colours all hold the solution vertex by vertex.
#include "radiosity/bake.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <tuple>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "image/tonemap.h"
#include "mesh_builders.h"
#include "radiosity/solver.h"
#include "test_files.h"

namespace bounce {
namespace {

using test_support::scratch_dir;

struct solved_box {
  scene s;
  patch_mesh mesh;
  std::shared_ptr<const radiosity_snapshot> solution;
};

// The Cornell box, solved by the hierarchical solver on a coarse mesh.
const solved_box& solved_cornell_box() {
  static const solved_box box = [] {
    solved_box b;
    b.s = test_support::default_cornell_box();
    const patch_mesh input = test_support::mesh_of(b.s, 120.0);
    radiosity_params p;
    p.method = solver_method::hierarchical;
    p.hierarchical.split_elements = true;
    auto solver = make_radiosity_solver(b.s, input, p);
    stop_criterion stop;
    stop.remaining = 1e-4;
    stop.max_steps = 200;
    run_solver(*solver, stop);
    b.mesh = solved_mesh(*solver);
    b.solution = make_snapshot(*solver);
    return b;
  }();
  return box;
}

// Per surface, a vertex's position and normal (rounded to floats) to its
// index in the mesh: what a written vertex is matched by.
using vertex_key = std::tuple<int, float, float, float, float, float, float>;
std::map<vertex_key, std::size_t> vertex_index(const patch_mesh& mesh) {
  std::map<vertex_key, std::size_t> out;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const vec3 &p = mesh.positions[v], &n = mesh.normals[v];
    out[{mesh.vertex_surfaces[v], float(p.x), float(p.y), float(p.z), float(n.x), float(n.y), float(n.z)}] = v;
  }
  return out;
}

const float* floats_of(const tinygltf::Model& m, int accessor) {
  const tinygltf::Accessor& a = m.accessors[std::size_t(accessor)];
  const tinygltf::BufferView& view = m.bufferViews[std::size_t(a.bufferView)];
  EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  return reinterpret_cast<const float*>(m.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset +
                                        a.byteOffset);
}

TEST(Bake, GltfVertexColoursHoldTheSolutionUnderAnUnlitMaterial) {
  const solved_box& box = solved_cornell_box();
  scratch_dir dir;
  const std::map<vertex_key, std::size_t> index = vertex_index(box.mesh);
  std::map<std::string, int> surface_of;
  for (std::size_t i = 0; i < box.s.surfaces.size(); ++i) surface_of[box.s.surfaces[i].name] = int(i);
  for (const char* name : {"lit.glb", "lit.gltf"}) {
    bake_settings settings;
    settings.parts = true;
    double exposure = 0.0;
    std::string error;
    const std::string path = dir.path(name);
    ASSERT_TRUE(write_bake(path, box.s, box.mesh, *box.solution, settings, error, &exposure)) << error;
    EXPECT_NEAR(exposure, bake_exposure(box.mesh, *box.solution, {}), 1e-12);
    for (const auto& entry : std::filesystem::directory_iterator(dir.root))
      EXPECT_EQ(entry.path().string().find(".partial"), std::string::npos) << entry.path();

    tinygltf::TinyGLTF loader;
    tinygltf::Model m;
    std::string err, warn;
    const bool ok = std::string(name).ends_with(".glb") ? loader.LoadBinaryFromFile(&m, &err, &warn, path)
                                                        : loader.LoadASCIIFromFile(&m, &err, &warn, path);
    ASSERT_TRUE(ok) << err;
    EXPECT_TRUE(err.empty()) << err;
    ASSERT_EQ(m.materials.size(), 1u);
    EXPECT_EQ(m.materials[0].extensions.count("KHR_materials_unlit"), 1u);
    EXPECT_EQ(m.extensionsUsed, std::vector<std::string>{"KHR_materials_unlit"});
    std::size_t checked = 0, triangles = 0;
    double worst = 0.0, worst_parts = 0.0;
    for (const tinygltf::Node& node : m.nodes) {
      ASSERT_TRUE(surface_of.count(node.name)) << node.name;  // named after its surface
      const int surface = surface_of[node.name];
      const tinygltf::Primitive& p = m.meshes[std::size_t(node.mesh)].primitives.at(0);
      EXPECT_EQ(p.material, 0);
      const std::size_t n = m.accessors[std::size_t(p.attributes.at("POSITION"))].count;
      const float* positions = floats_of(m, p.attributes.at("POSITION"));
      const float* normals = floats_of(m, p.attributes.at("NORMAL"));
      const float* colours = floats_of(m, p.attributes.at("COLOR_0"));
      const float* direct = floats_of(m, p.attributes.at("_DIRECT"));
      const float* indirect = floats_of(m, p.attributes.at("_INDIRECT"));
      for (std::size_t i = 0; i < n; ++i) {
        const float* x = positions + 3 * i;
        const float* nn = normals + 3 * i;
        const auto it = index.find({surface, x[0], x[1], x[2], nn[0], nn[1], nn[2]});
        ASSERT_NE(it, index.end()) << node.name << " vertex " << i;
        const rgb b = box.solution->radiosity[it->second];
        for (int c = 0; c < 3; ++c) {
          const double expected = std::clamp(b[c] / std::numbers::pi * exposure, 0.0, 1.0);
          worst = std::max(worst, std::abs(colours[3 * i + c] - expected));
          // The parts add up to the radiance times the exposure, unclamped.
          const double sum = direct[3 * i + c] + indirect[3 * i + c];
          worst_parts = std::max(worst_parts, std::abs(sum - b[c] / std::numbers::pi * exposure) /
                                                  std::max(1.0, b[c] / std::numbers::pi * exposure));
          EXPECT_NEAR(direct[3 * i + c], box.solution->direct[it->second][c] / std::numbers::pi * exposure,
                      1e-6 * (1.0 + direct[3 * i + c]));
        }
        ++checked;
      }
      triangles += m.accessors[std::size_t(p.indices)].count / 3;
    }
    // Float colours: to 1e-7 of the exact value.
    EXPECT_LT(worst, 1e-7) << name;
    EXPECT_LT(worst_parts, 1e-6) << name;
    EXPECT_EQ(triangles, box.mesh.element_count());
    EXPECT_EQ(checked, box.mesh.vertex_count());  // every vertex, once: a vertex belongs to one surface
  }
}

TEST(Bake, ObjAndPlyCarryTheSameColoursAsSrgb) {
  const solved_box& box = solved_cornell_box();
  scratch_dir dir;
  std::string error;
  ASSERT_TRUE(write_bake(dir.path("lit.obj"), box.s, box.mesh, *box.solution, {}, error)) << error;
  ASSERT_TRUE(write_bake(dir.path("lit.ply"), box.s, box.mesh, *box.solution, {}, error)) << error;
  const double exposure = bake_exposure(box.mesh, *box.solution, {});
  std::map<std::string, int> surface_of;
  for (std::size_t i = 0; i < box.s.surfaces.size(); ++i) surface_of[box.s.surfaces[i].name] = int(i);

  // OBJ: "o name", then "v x y z r g b" and "vn", faces "f a//a ...".
  std::ifstream obj(dir.path("lit.obj"));
  std::string line, object;
  std::vector<std::pair<vec3, rgb>> vertices;
  std::vector<vec3> normals;
  std::vector<int> surfaces;
  std::size_t faces = 0;
  while (std::getline(obj, line)) {
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    if (tag == "o") {
      object = line.substr(2);
      ASSERT_TRUE(surface_of.count(object)) << object;
    } else if (tag == "v") {
      vec3 p;
      rgb c;
      in >> p.x >> p.y >> p.z >> c.r >> c.g >> c.b;
      vertices.push_back({p, c});
      surfaces.push_back(surface_of[object]);
    } else if (tag == "vn") {
      vec3 n;
      in >> n.x >> n.y >> n.z;
      normals.push_back(n);
    } else if (tag == "f") {
      ++faces;
    }
  }
  EXPECT_EQ(faces, box.mesh.element_count());
  ASSERT_EQ(normals.size(), vertices.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    // Positions to 9 digits and normals to 6: the nearest vertex of the surface.
    std::size_t best = 0;
    double best_distance = INFINITY;
    for (std::size_t v = 0; v < box.mesh.vertex_count(); ++v) {
      if (box.mesh.vertex_surfaces[v] != surfaces[i]) continue;
      const double d =
          glm::length(box.mesh.positions[v] - vertices[i].first) + glm::length(box.mesh.normals[v] - normals[i]);
      if (d < best_distance) best_distance = d, best = v;
    }
    ASSERT_LT(best_distance, 1e-4);
    const rgb expected = baked_colour(box.solution->radiosity[best], exposure);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(vertices[i].second[c] - linear_to_srgb(expected[c])));
  }
  EXPECT_LT(worst, 1e-6);  // written to 6 decimals
  // PLY: the header names the same exposure; uchar colours are the same, to one level.
  const std::string ply = test_support::read_text(dir.path("lit.ply"));
  std::ostringstream exposure_text;
  exposure_text << "exposure " << exposure;
  EXPECT_NE(ply.find(exposure_text.str()), std::string::npos);
  EXPECT_NE(ply.find("element face " + std::to_string(box.mesh.element_count())), std::string::npos);
}

// Optional: where Blender is installed (it is not in CI), its own glTF
// importer reads the colours back: per corner, as sRGB bytes.
TEST(Bake, BlenderImportsTheVertexColours) {
  if (std::system("command -v blender > /dev/null 2>&1") != 0) GTEST_SKIP() << "no blender on PATH";
  const solved_box& box = solved_cornell_box();
  scratch_dir dir;
  std::string error;
  const std::string glb = dir.path("lit.glb");
  ASSERT_TRUE(write_bake(glb, box.s, box.mesh, *box.solution, {}, error)) << error;
  const double exposure = bake_exposure(box.mesh, *box.solution, {});
  const std::string script = dir.write("read.py", R"(import sys
import numpy
if not hasattr(numpy, "bool"): numpy.bool = bool  # Debian 12's Blender 3.4 still uses np.bool
import bpy
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=sys.argv[sys.argv.index("--") + 1])
with open(sys.argv[sys.argv.index("--") + 2], "w") as out:
    for ob in bpy.context.scene.objects:
        if ob.type != "MESH": continue
        me = ob.data
        colours = me.color_attributes[0]
        for loop in me.loops[:64]:
            p = me.vertices[loop.vertex_index].co
            c = colours.data[loop.index].color_srgb
            out.write("%s;%.9g %.9g %.9g %.9g %.9g %.9g\n" % (ob.name, p[0], p[1], p[2], c[0], c[1], c[2]))
)");
  const std::string listing = dir.path("colours.txt");
  const std::string command =
      "blender -b --factory-startup --python '" + script + "' -- '" + glb + "' '" + listing + "' > /dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream in(listing);
  std::string line;
  std::size_t read = 0;
  double worst = 0.0;
  while (std::getline(in, line)) {
    const std::string name = line.substr(0, line.find(';'));
    std::istringstream values(line.substr(line.find(';') + 1));
    vec3 b;  // Blender is z-up: glTF's (x, y, z) is its (x, -z, y)
    rgb c;
    values >> b.x >> b.y >> b.z >> c.r >> c.g >> c.b;
    const vec3 p(b.x, b.z, -b.y);
    // The surface's vertex there (Blender merges none; corners may share a position: the closest colour).
    double best = INFINITY;
    for (std::size_t v = 0; v < box.mesh.vertex_count(); ++v) {
      if (box.s.surfaces[std::size_t(box.mesh.vertex_surfaces[v])].name != name) continue;
      if (glm::length(box.mesh.positions[v] - p) > 1e-3) continue;
      const rgb expected = baked_colour(box.solution->radiosity[v], exposure);
      double d = 0.0;
      for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(c[k] - linear_to_srgb(expected[k])));
      best = std::min(best, d);
    }
    worst = std::max(worst, best);
    ++read;
  }
  EXPECT_GT(read, 100u);
  EXPECT_LE(worst, 1.0 / 255);  // Blender keeps bytes: within a level (measured 0.51 of one)
}

TEST(Bake, RefusesUnknownFormatsAndLeavesNoPartialFile) {
  const solved_box& box = solved_cornell_box();
  scratch_dir dir;
  std::string error;
  EXPECT_FALSE(write_bake(dir.path("lit.png"), box.s, box.mesh, *box.solution, {}, error));
  EXPECT_NE(error.find("lit.png: unknown bake format"), std::string::npos) << error;
  // A folder that does not exist: a clear error, nothing left behind.
  EXPECT_FALSE(write_bake(dir.path("missing/lit.glb"), box.s, box.mesh, *box.solution, {}, error));
  EXPECT_NE(error.find("missing/lit.glb: cannot open for writing"), std::string::npos) << error;
  // What is in the way stays as it was, and nothing is left beside it: a
  // folder of the target's name (the written file cannot replace it).
  const std::string folder = dir.path("taken.glb");
  std::filesystem::create_directory(folder);
  dir.write("taken.glb/inside", "kept");
  EXPECT_FALSE(write_bake(folder, box.s, box.mesh, *box.solution, {}, error));
  EXPECT_NE(error.find("taken.glb: cannot put the written file in place"), std::string::npos) << error;
  EXPECT_EQ(test_support::read_text(folder + "/inside"), "kept");
  for (const auto& entry : std::filesystem::directory_iterator(dir.root))
    EXPECT_EQ(entry.path().string().find(".partial"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace bounce
