// The JSON scene format, read through load_scene as `bounce scene.json`
// reads it: a round trip of every construct, and bad input that must fail
// with a message naming the file and the value's path inside it, or the
// line and column of a syntax error.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "mesh_builders.h"
#include "scene/scene_io.h"
#include "test_files.h"

namespace bounce {
namespace {

using test_support::json_scene;
using test_support::load_error_of;
using test_support::load_ok;
using test_support::scratch_dir;

TEST(JsonScene, RoundTripOfEveryShape) {
  scratch_dir dir;
  std::string points;
  for (int i = 0; i < 16; ++i)
    points += (i ? "," : "") + std::string("[") + std::to_string(i % 4) + "," + std::to_string(i / 4) + ",0]";
  std::string path = dir.write("s.json",
                               R"({
  "camera": {"eye": [0, 1, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fov": 30, "size": [320, 200]},
  "background": [0.1, 0.2, 0.3],
  "textures": {"checks": {"checker": {"color0": [1, 1, 1], "color1": [0.1, 0.1, 0.1], "scale": 4}}},
  "materials": {
    "floor": {"rho": [0.8, 0.7, 0.6], "texture": "checks"},
    "glass": {"kt": [0.9, 0.9, 0.9], "kr": [0.1, 0.1, 0.1], "ior": 1.5, "fresnel": true, "specular": [1, 1, 1], "shininess": 80},
    "lamp": {"ke": [2, 3, 4]}
  },
  "surfaces": [
    {"name": "floor", "polygon": [[-1,0,-1],[-1,0,1],[1,0,1],[1,0,-1]], "uv": [[0,0],[0,1],[1,1],[1,0]], "material": "floor"},
    {"sphere": {"center": [0, 1, 0], "radius": 0.5}, "material": "glass"},
    {"quadric": {"a": 1, "c": 1, "k": -0.25, "box": [[-1, 0, -1], [1, 2, 1]]}, "material": "floor"},
    {"bezier": {"points": [)" + points +
                                   R"(], "patches": [[0,1,2,3,4,5,6,7,8,9,10,11,12,13,14,15]]}, "material": "floor"},
    {"bspline": {"rows": 4, "cols": 4, "points": [)" +
                                   points + R"(]}, "material": "lamp"}
  ],
  "lights": [{"position": [0, 3, 0], "intensity": [5, 5, 5]}]
})");
  scene s = load_ok(path);
  EXPECT_EQ(s.view.width, 320);
  EXPECT_EQ(s.view.height, 200);
  EXPECT_EQ(s.view.fov_y_degrees, 30.0);
  EXPECT_EQ(s.background, rgb(0.1, 0.2, 0.3));
  ASSERT_EQ(s.surfaces.size(), 5u);
  EXPECT_EQ(s.surfaces[0].name, "floor");
  EXPECT_EQ(s.surfaces[1].name, "surfaces[1]");
  const auto& floor = std::get<polygon_mesh>(s.surfaces[0].geometry);
  EXPECT_EQ(floor.uvs[2], vec2(1, 1));
  EXPECT_EQ(s.materials[floor.faces[0].material].texture, 0);
  EXPECT_EQ(s.textures[0].scale, 4.0);
  const auto& ball = std::get<sphere>(s.surfaces[1].geometry);
  EXPECT_EQ(ball.radius, 0.5);
  EXPECT_TRUE(s.materials[ball.material].fresnel);
  EXPECT_EQ(s.materials[ball.material].shininess, 80.0);
  const auto& q = std::get<quadric>(s.surfaces[2].geometry);
  EXPECT_EQ(q.a, 1.0);
  EXPECT_EQ(q.b, 0.0);
  EXPECT_EQ(q.k, -0.25);
  EXPECT_EQ(q.box_max, vec3(1, 2, 1));
  const auto& bez = std::get<bezier_surface>(s.surfaces[3].geometry);
  EXPECT_EQ(bez.patches[0][7], vec3(3, 1, 0));
  const auto& bs = std::get<bspline_surface>(s.surfaces[4].geometry);
  EXPECT_EQ(bs.control[13], vec3(1, 3, 0));
  EXPECT_EQ(s.lights[0].intensity, rgb(5.0));
}

// ---- bad input -----------------------------------------------------------

TEST(JsonSceneBadInput, MalformedJsonNamesLineAndColumn) {
  scratch_dir dir;
  std::string path = dir.write("bad.json", "{\n  \"materials\": {\n    \"white\": {\"rho\": [0.5, 0.5 0.5]}\n}\n");
  std::string e = load_error_of(path);
  EXPECT_NE(e.find(path + ":3:"), std::string::npos) << e;
  EXPECT_NE(e.find("invalid JSON"), std::string::npos) << e;
}

TEST(JsonSceneBadInput, UnknownJsonKey) {
  scratch_dir dir;
  std::string path = dir.write(
      "s.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": 1, "colour": 3}, "material": "white"})"));
  std::string e = load_error_of(path);
  EXPECT_NE(e.find("surfaces[0].sphere"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key 'colour'"), std::string::npos) << e;
}

TEST(JsonSceneBadInput, WrongJsonType) {
  scratch_dir dir;
  std::string path =
      dir.write("s.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": "big"}, "material": "white"})"));
  std::string e = load_error_of(path);
  EXPECT_NE(e.find("surfaces[0].sphere.radius: must be a number"), std::string::npos) << e;
}

TEST(JsonSceneBadInput, InfiniteJsonNumber) {
  scratch_dir dir;
  std::string path =
      dir.write("s.json", json_scene(R"({"sphere": {"center": [0,1e999,0], "radius": 1}, "material": "white"})"));
  std::string e = load_error_of(path);
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_TRUE(e.find("finite") != std::string::npos || e.find("invalid JSON") != std::string::npos) << e;
}

TEST(JsonSceneBadInput, UnknownMaterialReference) {
  scratch_dir dir;
  std::string path =
      dir.write("s.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": 1}, "material": "gold"})"));
  std::string e = load_error_of(path);
  EXPECT_NE(e.find("surfaces[0].material: no material named 'gold'"), std::string::npos) << e;
}

TEST(JsonSceneBadInput, UndecodableTexture) {
  scratch_dir dir;
  dir.write("garbage.png", "this is not a png");
  std::string path = dir.write("s.json", R"({"textures": {"t": {"image": "garbage.png"}},
    "materials": {"m": {"rho": [0.5,0.5,0.5], "texture": "t"}},
    "surfaces": [{"sphere": {"center": [0,0,0], "radius": 1}, "material": "m"}],
    "lights": [{"position": [0,5,0], "intensity": [1,1,1]}]})");
  std::string e = load_error_of(path);
  EXPECT_NE(e.find("cannot decode texture"), std::string::npos) << e;
  EXPECT_NE(e.find("textures.t"), std::string::npos) << e;
}

// A 100,000-corner polygon took 43 s to triangulate: the OBJ reader's limit
// on corners holds for JSON polygons too.
TEST(JsonSceneBadInput, PolygonsHaveAtMostTheCornersOfAnObjFace) {
  scratch_dir dir;
  std::string circle = "[";
  for (int i = 0; i <= 10000; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 10001.0;
    circle += (i ? ", [" : "[") + std::to_string(std::cos(a)) + ", 0, " + std::to_string(std::sin(a)) + "]";
  }
  circle += "]";
  const std::string path =
      dir.write("circle.json", json_scene(R"({"polygon": )" + circle + R"(, "material": "white"})"));
  const std::string e = load_error_of(path);
  EXPECT_NE(e.find("surfaces[0].polygon: has 10001 corners; at most 10000"), std::string::npos) << e.substr(0, 300);
}

TEST(JsonScene, SpotAndSunLights) {
  scratch_dir dir;
  const std::string path =
      dir.write("lamps.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": 1}, "material": "white"})", R"(,
    "lights": [{"type": "spot", "position": [0, 4, 0], "intensity": [2, 2, 2], "direction": [0, -2, 0],
                "inner_cone_degrees": 10, "outer_cone_degrees": 20},
               {"type": "sun", "direction": [1, -1, 0], "irradiance": [3, 3, 3]}])"));
  const scene s = load_ok(path);
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].type, light_type::spot);
  EXPECT_EQ(s.lights[0].direction, vec3(0, -1, 0));
  EXPECT_NEAR(s.lights[0].inner_cone, 10 * std::numbers::pi / 180, 1e-15);
  EXPECT_NEAR(s.lights[0].outer_cone, 20 * std::numbers::pi / 180, 1e-15);
  EXPECT_EQ(s.lights[1].type, light_type::sun);
  EXPECT_NEAR(s.lights[1].direction.x, std::sqrt(0.5), 1e-15);
  EXPECT_EQ(s.lights[1].intensity, rgb(3.0));
  const std::string ball = R"({"sphere": {"center": [0,0,0], "radius": 1}, "material": "white"})";
  for (const auto& [light, message] : std::vector<std::pair<std::string, std::string>>{
           {R"({"type": "spot", "position": [0, 4, 0], "intensity": [1, 1, 1]})", "a spot light needs 'direction'"},
           {R"({"type": "spot", "position": [0, 4, 0], "intensity": [1, 1, 1], "direction": [0, -1, 0],
               "inner_cone_degrees": 30, "outer_cone_degrees": 20})",
            "spot cones need"},
           {R"({"type": "sun", "direction": [0, 0, 0], "irradiance": [1, 1, 1]})", "lights[0].direction: must be"},
           {R"({"type": "sun", "direction": [0, -1, 0], "intensity": [1, 1, 1]})", "unknown key 'intensity'"},
           {R"({"type": "area", "position": [0, 4, 0]})", "lights[0].type: 'area' is not a light type"}}) {
    const std::string bad = dir.write("bad.json", json_scene(ball, ", \"lights\": [" + light + "]"));
    const std::string e = load_error_of(bad);
    EXPECT_NE(e.find(message), std::string::npos) << e;
  }
}

// ---- h3: numbers in JSON scenes, messages that name the place ----

// Every number in a JSON scene is finite and at most max_file_number in
// magnitude, so that intensities, emissions, backgrounds and sizes cannot
// overflow (1e308 gave Inf and NaN pixels).
TEST(JsonSceneNumbers, HugeNumbersAreRefusedWithTheLimit) {
  scratch_dir dir;
  struct bad_case {
    const char* name;
    std::string json;
    const char* where;
  } cases[] = {
      {"light.json",
       R"({"surfaces": [{"sphere": {"center": [0,0,0], "radius": 1}, "material": "m"}],
           "materials": {"m": {"rho": [0.5,0.5,0.5]}},
           "lights": [{"position": [0,5,0], "intensity": [1e308, 1, 1]}]})",
       "lights[0].intensity[0]"},
      {"background.json",
       json_scene(R"({"sphere": {"center": [0,0,0], "radius": 1}, "material": "white"})",
                  R"(, "background": [0, 1e308, 0])"),
       "background[1]"},
      {"radius.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": 2e9}, "material": "white"})"),
       "surfaces[0].sphere.radius"},
      {"vertex.json", json_scene(R"({"polygon": [[0,0,0],[-5e9,0,0],[0,1,0]], "material": "white"})"),
       "surfaces[0].polygon[1][0]"},
  };
  for (const bad_case& c : cases) {
    const std::string path = dir.write(c.name, c.json);
    const std::string e = load_error_of(path);
    EXPECT_NE(e.find(path + ": " + c.where + ": "), std::string::npos) << e;
    EXPECT_NE(e.find("out of range (limit 1e+09 in magnitude)"), std::string::npos) << e;
  }
  // At the limit is fine.
  load_ok(dir.write("ok.json", json_scene(R"({"sphere": {"center": [0,0,0], "radius": 1}, "material": "white"})",
                                          R"(, "background": [1e9, 0, 0])")));
}

// A literal beyond a double: file:line:column and what it is, not the JSON
// library's exception text.
TEST(JsonSceneNumbers, OverflowingLiteralNamesLineAndColumn) {
  scratch_dir dir;
  const std::string path =
      dir.write("a.json",
                "{\n  \"materials\": {\"w\": {\"rho\": [0.5, 0.5, 0.5]}},\n  \"surfaces\": [{\"sphere\": "
                "{\"center\": [0, \"1e999\", 0], \"radius\": -1e400}, \"material\": \"w\"}]\n}\n");
  const std::string e = load_error_of(path);
  // Line 3; the string "1e999" before it is not a number.
  const std::string line3 = "  \"surfaces\": [{\"sphere\": {\"center\": [0, \"1e999\", 0], \"radius\": ";
  EXPECT_NE(e.find(path + ":3:" + std::to_string(line3.size() + 1) + ": number out of range: -1e400"),
            std::string::npos)
      << e;
  EXPECT_EQ(e.find("json.exception"), std::string::npos) << e;
}

// A missing OBJ names the scene file and the surface that refers to it.
TEST(JsonSceneNumbers, MissingObjNamesSceneAndSurface) {
  scratch_dir dir;
  const std::string path = dir.write(
      "a.json",
      json_scene(R"({"sphere": {"center": [0,0,0], "radius": 1}, "material": "white"}, {"obj": "gone.obj"})"));
  const std::string e = load_error_of(path);
  EXPECT_NE(e.find(path + ": surfaces[1].obj: "), std::string::npos) << e;
  EXPECT_NE(e.find("gone.obj"), std::string::npos) << e;
}

// Warnings said before a failure are kept for the caller to print first.
TEST(JsonSceneNumbers, WarningsBeforeAFailureAreKept) {
  scratch_dir dir;
  dir.write("m.mtl", "newmtl e\nKe 1 1 1\nKa 0 0 0\n");
  dir.write("w.obj", "mtllib m.mtl\nusemtl e\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string path = dir.write(
      "a.json", json_scene(R"({"obj": "w.obj"}, {"polygon": [[0,0,0],[1,0,0],[0,1,0]], "material": "nope"})"));
  scene s;
  load_report report;
  ASSERT_FALSE(load_scene(path, s, report));
  EXPECT_NE(report.error.find("no material named 'nope'"), std::string::npos) << report.error;
  ASSERT_FALSE(report.warnings.empty());
  EXPECT_NE(report.warnings[0].find("'Ka' is not used"), std::string::npos) << report.warnings[0];
}

}  // namespace
}  // namespace bounce
