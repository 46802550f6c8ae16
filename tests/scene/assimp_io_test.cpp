// PLY, STL, Collada, 3DS and OFF through assimp: small files written here,
// and every such model of Debian's assimp-testmodels when it is installed.
#include "scene/assimp_io.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "mesh_builders.h"
#include "scene/scene_io.h"
#include "test_files.h"

namespace bounce {
namespace {

using test_support::load_error_of;
using test_support::load_ok;
using test_support::scratch_dir;

double polygon_area(const scene& s) {
  double total = 0.0;
  for (const surface& surf : s.surfaces) {
    const auto* m = std::get_if<polygon_mesh>(&surf.geometry);
    if (!m) continue;
    for (const polygon_face& f : m->faces) {
      vec3 newell(0.0);
      for (std::size_t i = 0; i < f.position.size(); ++i)
        newell += glm::cross(m->positions[f.position[i]], m->positions[f.position[(i + 1) % f.position.size()]]);
      total += 0.5 * glm::length(newell);
    }
  }
  return total;
}

std::size_t face_count(const scene& s) {
  std::size_t n = 0;
  for (const surface& surf : s.surfaces)
    if (const auto* m = std::get_if<polygon_mesh>(&surf.geometry)) n += m->faces.size();
  return n;
}

// A unit cube as an OFF file: 8 corners, 6 quads, outward.
const char* cube_off = R"(OFF
8 6 0
0 0 0
1 0 0
1 1 0
0 1 0
0 0 1
1 0 1
1 1 1
0 1 1
4 0 3 2 1
4 4 5 6 7
4 0 1 5 4
4 2 3 7 6
4 1 2 6 5
4 0 4 7 3
)";

// OFF and PLY files without materials get assimp's default one, which is
// two-sided: each face comes with its back.
bool all_two_sided(const scene& s) {
  for (const material& m : s.materials)
    if (!m.two_sided) return false;
  return !s.materials.empty();
}

TEST(AssimpFormats, OffPlyAndStlOpenWithTheirFacesAndAreas) {
  scratch_dir dir;
  {
    const scene s = load_ok(dir.write("cube.off", cube_off));
    EXPECT_TRUE(all_two_sided(s));
    EXPECT_EQ(face_count(s), 2u * 6u);  // quads stay quads, each with its back
    EXPECT_NEAR(polygon_area(s), 2.0 * 6.0, 1e-9);
    EXPECT_GT(s.sky.zenith.r, 0.0);  // a model without lights opens under the white sky
  }
  {
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n2 0 0\n2 0 3\n0 0 3\n4 0 3 2 1\n";
    const scene s = load_ok(dir.write("quad.ply", ply));
    EXPECT_TRUE(all_two_sided(s));
    EXPECT_EQ(face_count(s), 2u);
    EXPECT_NEAR(polygon_area(s), 2.0 * 6.0, 1e-9);
  }
  {
    const std::string stl =
        "solid t\n"
        "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n"
        "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\n"
        "endsolid t\n";
    const scene s = load_ok(dir.write("square.stl", stl));
    EXPECT_FALSE(all_two_sided(s));  // assimp's STL material is one-sided
    EXPECT_EQ(face_count(s), 2u);
    EXPECT_NEAR(polygon_area(s), 1.0, 1e-9);
  }
}

// A binary 3DS file: one object of two triangles.
std::string two_triangles_3ds() {
  std::string out;
  auto u16 = [&](std::uint16_t v) { out.append(reinterpret_cast<const char*>(&v), 2); };
  auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  auto f32 = [&](float v) { out.append(reinterpret_cast<const char*>(&v), 4); };
  const std::uint32_t vertices = 6 + 2 + 4 * 12, faces = 6 + 2 + 2 * 8, mesh = 6 + vertices + faces,
                      object = 6 + 4 + mesh, editor = 6 + object, main = 6 + editor;
  u16(0x4D4D), u32(main);
  u16(0x3D3D), u32(editor);
  u16(0x4000), u32(object), out.append("box", 4);
  u16(0x4100), u32(mesh);
  u16(0x4110), u32(vertices), u16(4);
  const float corners[4][3] = {{0, 0, 0}, {4, 0, 0}, {4, 5, 0}, {0, 5, 0}};
  for (const auto& c : corners) f32(c[0]), f32(c[1]), f32(c[2]);
  u16(0x4120), u32(faces), u16(2);
  u16(0), u16(1), u16(2), u16(0);
  u16(0), u16(2), u16(3), u16(0);
  return out;
}

TEST(AssimpFormats, ThreeDsOpens) {
  scratch_dir dir;
  const scene s = load_ok(dir.write("two.3ds", two_triangles_3ds()));
  const double sides = all_two_sided(s) ? 2.0 : 1.0;
  EXPECT_EQ(face_count(s), std::size_t(2 * sides));
  EXPECT_NEAR(polygon_area(s), 20.0 * sides, 1e-6);
}

// Collada: a triangle whose material has a diffuse colour and one with an
// emission: rho and ke, and the emitter means no sky is added.
TEST(AssimpFormats, ColladaMaterialsBecomeReflectanceAndEmission) {
  scratch_dir dir;
  const std::string dae = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_effects>
    <effect id="red-fx"><profile_COMMON><technique sid="t"><lambert>
      <diffuse><color>0.8 0.1 0.1 1</color></diffuse></lambert></technique></profile_COMMON></effect>
    <effect id="lamp-fx"><profile_COMMON><technique sid="t"><lambert>
      <emission><color>5 5 5 1</color></emission>
      <diffuse><color>0.2 0.2 0.2 1</color></diffuse></lambert></technique></profile_COMMON></effect>
  </library_effects>
  <library_materials>
    <material id="red" name="red"><instance_effect url="#red-fx"/></material>
    <material id="lamp" name="lamp"><instance_effect url="#lamp-fx"/></material>
  </library_materials>
  <library_geometries>
    <geometry id="g"><mesh>
      <source id="p"><float_array id="pa" count="18">0 0 0  2 0 0  0 0 2  0 3 0  1 3 0  0 3 1</float_array>
        <technique_common><accessor source="#pa" count="6" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common></source>
      <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
      <triangles material="m0" count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 2 1</p></triangles>
      <triangles material="m1" count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>3 4 5</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="s"><node id="n">
    <instance_geometry url="#g"><bind_material><technique_common>
      <instance_material symbol="m0" target="#red"/>
      <instance_material symbol="m1" target="#lamp"/>
    </technique_common></bind_material></instance_geometry>
  </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)";
  const scene s = load_ok(dir.write("two.dae", dae));
  ASSERT_EQ(face_count(s), 2u);
  bool red = false, lamp = false;
  for (const material& m : s.materials) {
    red |= m.rho == rgb(0.8f, 0.1f, 0.1f) && m.ke == rgb(0.0);
    lamp |= m.ke == rgb(5.0) && m.rho == rgb(0.2f);
  }
  EXPECT_TRUE(red);
  EXPECT_TRUE(lamp);
  EXPECT_EQ(s.sky.zenith, rgb(0.0));  // it has its own light
}

TEST(AssimpFormats, BadFilesAreRefusedNamingTheFile) {
  scratch_dir dir;
  const std::string truncated = dir.write("cut.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n");
  EXPECT_NE(load_error_of(truncated).find("cut.ply"), std::string::npos);
  const std::string garbage = dir.write("noise.stl", std::string(40, '\x07'));
  EXPECT_NE(load_error_of(garbage).find("noise.stl"), std::string::npos);
  EXPECT_NE(load_error_of(dir.path("missing.off")).find("missing.off"), std::string::npos);
  std::filesystem::create_directories(dir.path("folder.dae"));
  EXPECT_NE(load_error_of(dir.path("folder.dae")).find("not a regular file"), std::string::npos);
}

// Every PLY, STL, Collada, 3DS, OFF and FBX model of Debian's
// assimp-testmodels (installed by third_party/install-deps.sh): each opens,
// or is refused with a message naming it; none crashes or hangs. The
// counts go to docs/scene-format.md.
TEST(AssimpFormats, EveryCorpusModelOpensOrIsRefusedByName) {
  const std::filesystem::path root = "/usr/share/assimp/models";
  if (!std::filesystem::is_directory(root)) GTEST_SKIP() << "assimp-testmodels is not installed";
  std::map<std::string, std::pair<int, int>> counts;  // extension -> (opened, refused)
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file() || !read_through_assimp(entry.path().string())) continue;
    const std::string path = entry.path().string();
    if (path.find("/invalid/") != std::string::npos) continue;
    scene s;
    load_report report;
    const bool ok = load_scene(path, s, report);
    std::string ext = entry.path().extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    (ok ? counts[ext].first : counts[ext].second) += 1;
    if (!ok) {
      EXPECT_NE(report.error.find(path), std::string::npos) << report.error;
      std::printf("  refused %s\n", report.error.c_str());
    }
  }
  for (const auto& [ext, c] : counts) std::printf("  %s: %d opened, %d refused\n", ext.c_str(), c.first, c.second);
  // Measured: every 3DS; all but 1 STL, 1 FBX, 1 OFF, 3 PLY and 4 Collada
  // files (points or lights only, malformed, or beyond assimp 5.2).
  EXPECT_GE(counts[".3ds"].first, 9);
  EXPECT_GE(counts[".dae"].first, 21);
  EXPECT_GE(counts[".fbx"].first, 18);
  EXPECT_GE(counts[".off"].first, 2);
  EXPECT_GE(counts[".ply"].first, 5);
  EXPECT_GE(counts[".stl"].first, 7);
}

}  // namespace
}  // namespace bounce
