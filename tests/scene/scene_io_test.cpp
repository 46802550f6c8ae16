// Scene loading: the shipped scenes, OBJ round trips, generated scenes,
// and every kind of bad input (each must fail with a message that names
// the file and the line or object). The JSON format's own cases are in
// json_scene_test.cpp, the fitted camera's in framing_test.cpp.
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include "base/embedded.h"
#include "mesh_builders.h"
#include "scene/procedural.h"
#include "scene/scene_info.h"
#include "scene/scene_io.h"
#include "scene/scene_validate.h"
#include "test_files.h"

namespace bounce {
namespace {

using test_support::json_scene;
using test_support::load_error_of;
using test_support::load_ok;
using test_support::scratch_dir;
using test_support::source_path;

const char* simple_mtl = R"(newmtl white
Kd 0.5 0.5 0.5
newmtl light
Kd 0.2 0.2 0.2
Ke 10 10 10
)";

const char* simple_obj = R"(mtllib simple.mtl
v 0 0 0
v 1 0 0
v 1 0 1
v 0 0 1
v 0 1 0
v 1 1 0
v 1 1 1
o floor
usemtl white
f 1 4 3 2
o light
usemtl light
f 5 6 7
)";

const polygon_mesh& mesh_of(const scene& s, const std::string& name) {
  for (const surface& surf : s.surfaces)
    if (surf.name == name) return std::get<polygon_mesh>(surf.geometry);
  ADD_FAILURE() << "no surface " << name;
  static polygon_mesh empty;
  return empty;
}

TEST(SceneIo, CornellBoxAsset) {
  scene s = load_ok(source_path("assets/cornell_box/cornell_box.json"));
  scene_summary sum;
  ASSERT_EQ(summarize_scene(s, default_max_edge(s), sum), "");
  EXPECT_EQ(sum.polygon_meshes, sum.surfaces);
  EXPECT_EQ(sum.emitting_surfaces, 1u);
  EXPECT_EQ(sum.emitting_materials, 1u);
  EXPECT_EQ(s.view.eye, vec3(278, 273, -800));
  EXPECT_NEAR(s.view.fov_y_degrees, 39.3, 1e-12);
  // The light is radiance (17, 12, 4) as in the Cornell data.
  bool found = false;
  for (const material& m : s.materials)
    if (m.ke == rgb(17, 12, 4)) found = true;
  EXPECT_TRUE(found);
  EXPECT_NEAR(sum.bounds.max.y, 548.8, 1e-9);
  EXPECT_NEAR(sum.bounds.min.y, 0.0, 1e-9);
}

// Every room face points into the box, every block face out of its block.
TEST(SceneIo, CornellBoxNormalsPointIntoTheRoom) {
  scene s = load_ok(source_path("assets/cornell_box/cornell_box.json"));
  const vec3 room_centre(278, 274, 280);
  for (const surface& surf : s.surfaces) {
    const auto& mesh = std::get<polygon_mesh>(surf.geometry);
    vec3 object_centre(0.0);
    for (const vec3& p : mesh.positions) object_centre += p;
    object_centre /= double(mesh.positions.size());
    const bool block = surf.name.find("block") != std::string::npos;
    for (const polygon_face& f : mesh.faces) {
      vec3 newell(0.0), centroid(0.0);
      for (std::size_t i = 0; i < f.position.size(); ++i) {
        newell += glm::cross(mesh.positions[f.position[i]], mesh.positions[f.position[(i + 1) % f.position.size()]]);
        centroid += mesh.positions[f.position[i]];
      }
      centroid /= double(f.position.size());
      double facing = block ? glm::dot(newell, centroid - object_centre) : glm::dot(newell, room_centre - centroid);
      EXPECT_GT(facing, 0.0) << surf.name << " line " << f.line;
    }
  }
}

TEST(SceneIo, EmbeddedDefaultMatchesAssetFiles) {
  ASSERT_FALSE(embedded_files().empty());
  for (const embedded_file& f : embedded_files()) {
    std::ifstream in(source_path("assets/" + std::string(f.path)), std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    EXPECT_EQ(bytes.str(), f.contents) << f.path;
  }
  scene embedded = load_ok(default_scene_path);
  scene asset = load_ok(source_path("assets/cornell_box/cornell_box.json"));
  ASSERT_EQ(embedded.surfaces.size(), asset.surfaces.size());
  for (std::size_t i = 0; i < asset.surfaces.size(); ++i) {
    EXPECT_EQ(embedded.surfaces[i].name, asset.surfaces[i].name);
    EXPECT_EQ(std::get<polygon_mesh>(embedded.surfaces[i].geometry).positions,
              std::get<polygon_mesh>(asset.surfaces[i].geometry).positions);
  }
  EXPECT_EQ(embedded.view.eye, asset.view.eye);
}

TEST(SceneIo, EveryShippedSceneLoads) {
  for (const char* path :
       {"assets/cornell_box/cornell_box.json", "assets/cornell_box/cornell_box.obj", "assets/furnace/furnace.json",
        "assets/whitted/whitted.json", "assets/teapot/teapot.json", "assets/shapes/shapes.json"}) {
    scene s;
    load_report report;
    EXPECT_TRUE(load_scene(source_path(path), s, report)) << report.error;
    EXPECT_EQ(report.dropped_faces, 0u) << path;
  }
}

TEST(SceneIo, ObjRoundTrip) {
  scratch_dir dir;
  dir.write("simple.mtl", simple_mtl);
  std::string path = dir.write("simple.obj", simple_obj);
  scene s = load_ok(path);
  ASSERT_EQ(s.surfaces.size(), 2u);
  const polygon_mesh& floor = mesh_of(s, "floor");
  ASSERT_EQ(floor.faces.size(), 1u);
  EXPECT_EQ(floor.faces[0].position.size(), 4u);  // quads stay quads
  EXPECT_EQ(floor.positions.size(), 4u);          // only the object's own vertices
  EXPECT_EQ(floor.positions[floor.faces[0].position[1]], vec3(0, 0, 1));
  EXPECT_EQ(floor.faces[0].line, 11);
  EXPECT_EQ(s.materials[floor.faces[0].material].name, "white");
  const polygon_mesh& light = mesh_of(s, "light");
  EXPECT_EQ(s.materials[light.faces[0].material].ke, rgb(10.0));
  EXPECT_EQ(s.materials[floor.faces[0].material].rho, rgb(0.5));
}

TEST(SceneIo, ObjCornerFormsAndNegativeIndices) {
  scratch_dir dir;
  dir.write("m.mtl", "newmtl e\nKe 1 1 1\n");
  std::string path = dir.write("m.obj", R"(mtllib m.mtl
usemtl e
v 0 0 0
v 1 0 0
v 0 1 0
vt 0 0
vt 1 0
vt 0 1
vn 0 0 2
f -3/-3/-1 -2/-2/-1 -1/-1/-1
f 1//1 2//1 3//1
f 1/1 2/2 3/3
)");
  scene s = load_ok(path);
  const auto& mesh = std::get<polygon_mesh>(s.surfaces[0].geometry);
  ASSERT_EQ(mesh.faces.size(), 3u);
  EXPECT_EQ(mesh.faces[0].position, mesh.faces[1].position);
  EXPECT_EQ(mesh.faces[0].uv.size(), 3u);
  EXPECT_EQ(mesh.faces[1].uv.size(), 0u);
  EXPECT_EQ(mesh.faces[2].normal.size(), 0u);
  EXPECT_EQ(mesh.normals[mesh.faces[0].normal[0]], vec3(0, 0, 1));  // normalised
  EXPECT_EQ(mesh.uvs[mesh.faces[0].uv[2]], vec2(0, 1));
}

TEST(SceneIo, MtlIlluminationModels) {
  scratch_dir dir;
  dir.write("m.mtl", R"(newmtl matte
Kd 0.5 0.5 0.5
Ks 0.3 0.3 0.3
illum 1
newmtl shiny
Kd 0.5 0.5 0.5
Ks 0.3 0.3 0.3
Ns 50
illum 2
newmtl mirror
Kd 0.1 0.1 0.1
Ks 0.8 0.8 0.8
illum 3
newmtl glass
Kd 0 0 0
Ks 0.1 0.1 0.1
Ni 1.5
d 0.1
illum 7
newmtl lamp
Ke 5 4 3
Tr 0
)");
  std::string path = dir.write("m.obj", "mtllib m.mtl\nusemtl lamp\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  scene s = load_ok(path);
  auto find = [&](const std::string& name) {
    for (const material& m : s.materials)
      if (m.name == name) return m;
    ADD_FAILURE() << name;
    return material{};
  };
  EXPECT_EQ(find("matte").specular, rgb(0.0));
  EXPECT_EQ(find("matte").kr, rgb(0.0));
  EXPECT_EQ(find("shiny").specular, rgb(0.3));
  EXPECT_EQ(find("shiny").shininess, 50.0);
  EXPECT_EQ(find("shiny").kr, rgb(0.0));
  EXPECT_EQ(find("mirror").kr, rgb(0.8));
  EXPECT_EQ(find("glass").ior, 1.5);
  EXPECT_NEAR(find("glass").kt.r, 0.9, 1e-12);
  EXPECT_TRUE(find("glass").fresnel);
  EXPECT_EQ(find("lamp").ke, rgb(5, 4, 3));
  EXPECT_EQ(find("lamp").kt, rgb(0.0));
}

TEST(SceneIo, GeneratedNameBuildsTheProceduralScene) {
  scene s;
  load_report report;
  ASSERT_TRUE(load_scene("generated:box-room-3", s, report)) << report.error;
  EXPECT_TRUE(report.warnings.empty());
  EXPECT_EQ(s.source, "generated:box-room-3");  // reopening it builds it again
  EXPECT_EQ(triangle_count(s), box_room_fixed_triangles + 9 * box_room_triangles_per_box);
  // The same scene as built by name, camera included.
  const scene direct = make_box_room(3);
  EXPECT_EQ(s.surfaces.size(), direct.surfaces.size());
  EXPECT_EQ(s.materials.size(), direct.materials.size());
  EXPECT_EQ(s.view.eye, direct.view.eye);
  ASSERT_TRUE(load_scene("generated:interior-10k", s, report)) << report.error;
  EXPECT_NEAR(double(triangle_count(s)), 10'000.0, 100.0);
}

TEST(SceneIo, ImageTextureIsDecodedToLinear) {
  scratch_dir dir;
  // 2x1 PNG: sRGB 255 (linear 1) and sRGB 128 (linear 0.2158).
  const unsigned char pixels[] = {255, 255, 255, 128, 0, 64};
  ASSERT_TRUE(stbi_write_png(dir.path("t.png").c_str(), 2, 1, 3, pixels, 6));
  dir.write("m.mtl", "newmtl tex\nKd 0.5 0.5 0.5\nKe 1 1 1\nmap_Kd -s 1 1 1 t.png\n");
  scene s = load_ok(dir.write("m.obj", "mtllib m.mtl\nusemtl tex\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  ASSERT_EQ(s.textures.size(), 1u);
  const texture& t = s.textures[0];
  EXPECT_EQ(t.kind, texture_kind::image);
  EXPECT_EQ(t.width, 2);
  EXPECT_EQ(t.height, 1);
  EXPECT_FLOAT_EQ(t.texels[0], 1.0f);
  EXPECT_NEAR(t.texels[3], 0.2158, 1e-4);
  EXPECT_EQ(t.texels[4], 0.0f);
  EXPECT_NEAR(t.texels[5], 0.0513, 1e-4);
  EXPECT_EQ(s.materials[0].texture, 0);
}

// ---- bad input -----------------------------------------------------------

TEST(SceneIoBadInput, MissingFile) {
  std::string e = load_error_of("/nonexistent/scene.json");
  EXPECT_NE(e.find("/nonexistent/scene.json"), std::string::npos) << e;
  EXPECT_NE(e.find("cannot read"), std::string::npos) << e;
}

TEST(SceneIoBadInput, UnknownFormat) {
  scratch_dir dir;
  std::string e = load_error_of(dir.write("scene.txt", "hello"));
  EXPECT_NE(e.find("unknown scene format"), std::string::npos) << e;
}

TEST(SceneIoBadInput, UnknownGeneratedNameIsNamed) {
  std::string e = load_error_of("generated:castle-12");
  EXPECT_EQ(e.rfind("generated:castle-12: ", 0), 0u) << e;
  EXPECT_NE(e.find("unknown procedural scene 'castle-12'"), std::string::npos) << e;
  e = load_error_of("generated:interior-12q");
  EXPECT_NE(e.find("'12q' is not a triangle count"), std::string::npos) << e;
  // Only the prefix selects it: a file of that name elsewhere is a file.
  e = load_error_of("/tmp/generated:box-room-3");
  EXPECT_NE(e.find("unknown scene format"), std::string::npos) << e;
}

TEST(SceneIoBadInput, MissingObjAndMtlAndTexture) {
  scratch_dir dir;
  std::string e = load_error_of(dir.write("a.json", json_scene(R"({"obj": "nothere.obj"})")));
  EXPECT_NE(e.find("nothere.obj"), std::string::npos) << e;

  // A missing material library is a warning (other programs open such
  // files); a missing texture an error.
  std::string obj = dir.write("b.obj", "mtllib nothere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  scene s;
  load_report report;
  ASSERT_TRUE(load_scene(obj, s, report)) << report.error;
  ASSERT_FALSE(report.warnings.empty());
  EXPECT_NE(report.warnings[0].find(obj + ":1: cannot read material library"), std::string::npos) << report.warnings[0];
  EXPECT_NE(report.warnings[0].find("nothere.mtl"), std::string::npos) << report.warnings[0];

  dir.write("c.mtl", "newmtl t\nKd 0.5 0.5 0.5\nmap_Kd nothere.png\n");
  e = load_error_of(dir.write("c.obj", "mtllib c.mtl\n"));
  EXPECT_NE(e.find("c.mtl:3: cannot read texture"), std::string::npos) << e;
}

TEST(SceneIoBadInput, ObjNanAndMalformedNumbersNameTheLine) {
  scratch_dir dir;
  std::string e = load_error_of(dir.write("nan.obj", "v 0 0 0\nv 1 nan 0\n"));
  EXPECT_NE(e.find("nan.obj:2: 'nan' is not a finite number"), std::string::npos) << e;
  e = load_error_of(dir.write("abc.obj", "v 0 0 0\n\nv 1 abc 0\n"));
  EXPECT_NE(e.find("abc.obj:3: 'abc' is not a number"), std::string::npos) << e;
  e = load_error_of(dir.write("short.obj", "v 0 0\n"));
  EXPECT_NE(e.find("short.obj:1: 'v' needs 3 to 6 numbers, got 2"), std::string::npos) << e;
}

TEST(SceneIoBadInput, ObjIndexOutOfRangeAndUndefinedMaterial) {
  scratch_dir dir;
  std::string e = load_error_of(dir.write("i.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"));
  EXPECT_NE(e.find("i.obj:4: vertex index 4 is out of range"), std::string::npos) << e;
  e = load_error_of(dir.write("z.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"));
  EXPECT_NE(e.find("z.obj:4:"), std::string::npos) << e;
  e = load_error_of(dir.write("mixed.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n"));
  EXPECT_NE(e.find("mixed.obj:5: every corner"), std::string::npos) << e;
}

TEST(SceneIoBadInput, ReflectanceOfOneOrMoreIsRejected) {
  // (MTL's Kd 1 is clamped instead: see ObjCorpus.KdOfOneIsClampedWithAWarning.)
  scratch_dir dir;
  std::string e;
  std::string path = dir.write("s.json", R"({"materials": {"m": {"rho": [0.5, 1.2, 0.5]}},
    "surfaces": [{"sphere": {"center": [0,0,0], "radius": 1}, "material": "m"}],
    "lights": [{"position": [0,5,0], "intensity": [1,1,1]}]})");
  e = load_error_of(path);
  EXPECT_NE(e.find("material 'm': rho"), std::string::npos) << e;
}

TEST(SceneIoBadInput, EnergyCreatingCombinationsAreRejected) {
  scratch_dir dir;
  std::string path = dir.write("s.json", R"({"materials": {"m": {"rho": [0.5, 0.5, 0.5], "kr": [0.6, 0.1, 0.1]}},
    "surfaces": [{"sphere": {"center": [0,0,0], "radius": 1}, "material": "m"}],
    "lights": [{"position": [0,5,0], "intensity": [1,1,1]}]})");
  std::string e = load_error_of(path);
  EXPECT_NE(e.find("material 'm': rho + kr + kt exceeds 1"), std::string::npos) << e;
}

TEST(SceneIoBadInput, NegativeEmission) {
  scratch_dir dir;
  std::string path = dir.write("s.json", R"({"materials": {"m": {"ke": [1, -1, 1]}},
    "surfaces": [{"sphere": {"center": [0,0,0], "radius": 1}, "material": "m"}]})");
  std::string e = load_error_of(path);
  EXPECT_NE(e.find("material 'm': emission ke"), std::string::npos) << e;
}

TEST(SceneIoBadInput, NoEmitterAndNoLightIsAWarning) {
  scratch_dir dir;
  std::string path = dir.write("s.json", R"({"materials": {"m": {"rho": [0.5, 0.5, 0.5]}},
    "surfaces": [{"sphere": {"center": [0,0,0], "radius": 1}, "material": "m"}]})");
  scene s;
  load_report report;
  ASSERT_TRUE(load_scene(path, s, report)) << report.error;
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_EQ(report.warnings[0].find(path + ": no emitter"), 0u) << report.warnings[0];
  EXPECT_FALSE(has_light_source(s));
}

TEST(SceneIoBadInput, DegenerateFacesAreDroppedWithAWarning) {
  scratch_dir dir;
  dir.write("m.mtl", "newmtl e\nKe 1 1 1\n");
  std::string path = dir.write("d.obj", R"(mtllib m.mtl
usemtl e
v 0 0 0
v 1 0 0
v 0 1 0
v 2 0 0
f 1 2 3
f 1 2 4
f 1 1 2
f 1 2
)");
  scene s;
  load_report report;
  ASSERT_TRUE(load_scene(path, s, report)) << report.error;
  EXPECT_EQ(report.dropped_faces, 3u);
  EXPECT_EQ(std::get<polygon_mesh>(s.surfaces[0].geometry).faces.size(), 1u);
  std::string all;
  for (const std::string& w : report.warnings) all += w + "\n";
  EXPECT_NE(all.find(path + ":8: degenerate face"), std::string::npos) << all;
  EXPECT_NE(all.find(path + ":9: degenerate face"), std::string::npos) << all;
  EXPECT_NE(all.find(path + ":10: face with 2 corners dropped"), std::string::npos) << all;
}

TEST(SceneIoBadInput, OnlyDegenerateFacesIsAnError) {
  scratch_dir dir;
  dir.write("m.mtl", "newmtl e\nKe 1 1 1\n");
  std::string e = load_error_of(dir.write("d.obj", "mtllib m.mtl\nusemtl e\nv 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"));
  EXPECT_NE(e.find("no surfaces left"), std::string::npos) << e;
}

TEST(SceneIoBadInput, AbsurdSizes) {
  scratch_dir dir;
  std::string e = load_error_of(
      dir.write("a.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": 1}, "material": "white"})",
                                     R"(, "camera": {"eye": [0,0,5], "target": [0,0,0], "size": [100000, 100000]})")));
  EXPECT_NE(e.find("camera: size 100000x100000"), std::string::npos) << e;

  e = load_error_of(dir.write(
      "b.json", json_scene(R"({"bspline": {"rows": 100000, "cols": 4, "points": []}, "material": "white"})")));
  EXPECT_NE(e.find("surfaces[0].bspline: rows and cols"), std::string::npos) << e;

  e = load_error_of(
      dir.write("c.json", json_scene(R"({"sphere": {"center": [0,0,1e300], "radius": 1}, "material": "white"})")));
  EXPECT_NE(e.find("surfaces[0].sphere.center[2]: 1e+300 is out of range"), std::string::npos) << e;

  // A scene that loads but whose tessellation would be absurd is refused.
  scene s =
      load_ok(dir.write("d.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": 1}, "material": "white"})")));
  scene_summary sum;
  std::string problem = summarize_scene(s, 1e-6, sum);
  EXPECT_NE(problem.find("use a larger --max-edge"), std::string::npos) << problem;
}

TEST(SceneIoBadInput, BadCamera) {
  scratch_dir dir;
  std::string e = load_error_of(
      dir.write("a.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": 1}, "material": "white"})",
                                     R"(, "camera": {"eye": [0,0,0], "target": [0,0,0]})")));
  EXPECT_NE(e.find("camera: eye and target are the same point"), std::string::npos) << e;
  e = load_error_of(
      dir.write("b.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": 1}, "material": "white"})",
                                     R"(, "camera": {"eye": [0,5,0], "target": [0,0,0]})")));
  EXPECT_NE(e.find("up is parallel"), std::string::npos) << e;
}

TEST(SceneIoBadInput, BadShapes) {
  scratch_dir dir;
  std::string e = load_error_of(
      dir.write("a.json", json_scene(R"({"quadric": {"a": 1, "box": [[1,1,1],[0,0,0]]}, "material": "white"})")));
  EXPECT_NE(e.find("box min must be below max"), std::string::npos) << e;
  e = load_error_of(
      dir.write("b.json", json_scene(R"({"quadric": {"k": 1, "box": [[0,0,0],[1,1,1]]}, "material": "white"})")));
  EXPECT_NE(e.find("no surface"), std::string::npos) << e;
  e = load_error_of(dir.write(
      "c.json",
      json_scene(
          R"({"bezier": {"points": [[0,0,0]], "patches": [[0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,99]]}, "material": "white"})")));
  EXPECT_NE(e.find("surfaces[0].bezier.patches[0][15]: index 99 is out of range"), std::string::npos) << e;
  e = load_error_of(
      dir.write("d.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": -1}, "material": "white"})")));
  EXPECT_NE(e.find("radius must be positive"), std::string::npos) << e;
  e = load_error_of(dir.write(
      "e.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": 1}, "polygon": [], "material": "white"})")));
  EXPECT_NE(e.find("exactly one shape key"), std::string::npos) << e;
  e = load_error_of(dir.write("f.json", json_scene(R"({"polygon": [[0,0,0],[1,0,0]], "material": "white"})")));
  EXPECT_NE(e.find("surfaces[0].polygon: needs at least 3 vertices"), std::string::npos) << e;
}

// The scene file is named once (validate's messages used to add the
// surface's file, which for a JSON surface is the same file).
TEST(SceneIoBadInput, ShapeErrorsNameTheFileOnce) {
  scratch_dir dir;
  const std::string path =
      dir.write("a.json", json_scene(R"({"quadric": {"a": 1, "box": [[1,1,1],[0,0,0]]}, "material": "white"})"));
  const std::string e = load_error_of(path);
  EXPECT_EQ(e.find(path), 0u) << e;
  EXPECT_EQ(e.find(path, 1), std::string::npos) << e;
}

// Scenes built in code get the same limits, printed short (%g).
TEST(SceneIoBadInput, ValidateRefusesHugeEmissionBriefly) {
  scene s;
  s.materials.push_back({});
  s.materials[0].name = "sun";
  s.materials[0].ke = rgb(1e300, 1.0, 1.0);
  s.surfaces.push_back({"ball", "", sphere{vec3(0.0), 1.0, 0}});
  s.view.eye = vec3(0, 0, 5);
  const std::string e = validate_scene(s);
  EXPECT_NE(e.find("material 'sun': emission ke (1e+300, 1, 1) is above the limit of 1e+09"), std::string::npos) << e;
  s.materials[0].ke = rgb(1e9, 0.0, 0.0);
  EXPECT_EQ(validate_scene(s), "");
}

// ---- h3: messages that name the place ----

// An emitter whose light reaches nothing (it faces away from everything)
// loads, with a warning naming it; turned round, no warning.
TEST(SceneIoNumbers, EmitterFacingAwayFromEverythingIsWarnedAbout) {
  scratch_dir dir;
  auto scene_with_lamp = [](const char* lamp) {
    return std::string(R"({"materials": {"w": {"rho": [0.5,0.5,0.5]}, "e": {"ke": [10,10,10]}},
      "surfaces": [{"name": "floor", "polygon": [[0,0,0],[0,0,1],[1,0,1],[1,0,0]], "material": "w"},
                   {"name": "lamp", "polygon": )") +
           lamp + R"(, "material": "e"}]})";
  };
  // Corners anticlockwise seen from above: light leaves upwards, away from the floor.
  load_report report;
  scene s;
  ASSERT_TRUE(load_scene(dir.write("away.json", scene_with_lamp("[[0.4,1,0.4],[0.4,1,0.6],[0.6,1,0.6],[0.6,1,0.4]]")),
                         s, report))
      << report.error;
  bool warned = false;
  for (const std::string& w : report.warnings)
    warned =
        warned || (w.find("surface 'lamp'") != std::string::npos && w.find("reaches nothing") != std::string::npos);
  EXPECT_TRUE(warned);
  ASSERT_TRUE(load_scene(dir.write("toward.json", scene_with_lamp("[[0.4,1,0.4],[0.6,1,0.4],[0.6,1,0.6],[0.4,1,0.6]]")),
                         s, report))
      << report.error;
  for (const std::string& w : report.warnings) EXPECT_EQ(w.find("reaches nothing"), std::string::npos) << w;
  // A floor turned away from the lamp receives nothing either.
  std::string flipped = scene_with_lamp("[[0.4,1,0.4],[0.6,1,0.4],[0.6,1,0.6],[0.4,1,0.6]]");
  flipped.replace(flipped.find("[[0,0,0],[0,0,1],[1,0,1],[1,0,0]]"), 33, "[[0,0,0],[1,0,0],[1,0,1],[0,0,1]]");
  ASSERT_TRUE(load_scene(dir.write("floor_down.json", flipped), s, report)) << report.error;
  warned = false;
  for (const std::string& w : report.warnings) warned = warned || w.find("reaches nothing") != std::string::npos;
  EXPECT_TRUE(warned);
  // The shipped scenes light what they hold.
  for (const char* shipped : {"assets/cornell_box/cornell_box.json", "assets/cornell_box/cornell_box.obj",
                              "assets/furnace/furnace.json", "assets/shapes/shapes.json", "assets/teapot/teapot.json",
                              "assets/whitted/whitted.json", "assets/bench/occluders.json",
                              "assets/bench/squares_parallel.json", "assets/bench/squares_perpendicular.json"}) {
    ASSERT_TRUE(load_scene(source_path(shipped), s, report)) << report.error;
    for (const std::string& w : report.warnings) EXPECT_EQ(w.find("reaches nothing"), std::string::npos) << w;
  }
}

}  // namespace
}  // namespace bounce
