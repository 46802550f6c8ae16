// Mutation fuzzing of every reader a user's file goes through: OBJ, MTL,
// JSON scenes, glTF (.gltf and .glb) and PFM. Seed files are mutated
// deterministically (flipped, deleted, repeated and inserted bytes,
// numbers swapped for extreme ones, truncation) and loaded. A mutant must
// load, or be refused with a message that names its file; nothing may
// crash, hang or leave a non-finite position in a loaded scene. CI runs it
// under AddressSanitizer and UBSan. BOUNCE_FUZZ_MUTANTS sets the mutants
// per seed (default 150) for longer runs.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gltf_builder.h"
#include "image/image.h"
#include "scene/scene_io.h"
#include "test_files.h"

namespace bounce {
namespace {

using test_support::scratch_dir;

int mutants_per_seed() {
  const char* count = std::getenv("BOUNCE_FUZZ_MUTANTS");
  return count && std::atoi(count) > 0 ? std::atoi(count) : 150;
}

// One to three random edits of `text`.
std::string mutate(std::string text, std::mt19937_64& random) {
  static const char* numbers[] = {
      "0",    "-1", "1e308", "-1e308", "nan", "inf", "1e-320", "4294967296", "-2147483649", "99999999999999999999",
      "0x10", "",   "-0",    "1e",     ".",   "+"};
  static const char* inserts[] = {"\n", "\r", "\r\n", "{", "}", "[", "]", "\"", ",", "#", " ", "\t", "/", "\\"};
  auto at = [&](std::size_t n) { return n == 0 ? std::size_t(0) : std::size_t(random() % n); };
  const int edits = 1 + int(random() % 3);
  for (int e = 0; e < edits && !text.empty(); ++e) {
    const std::size_t i = at(text.size());
    switch (random() % 7) {
      case 0:
        text[i] = char(random() & 0xff);
        break;
      case 1:
        text.erase(i, 1 + at(16));
        break;
      case 2:
        text.insert(i, text.substr(i, 1 + at(32)));
        break;
      case 3:
        text.insert(i, inserts[at(std::size(inserts))]);
        break;
      case 4: {
        // A number (a run of digits, signs, points and exponents) replaced.
        std::size_t start = i;
        while (start < text.size() && !std::isdigit(static_cast<unsigned char>(text[start]))) ++start;
        if (start == text.size()) break;
        std::size_t end = start;
        while (end < text.size() && std::string_view("0123456789.-+eE").find(text[end]) != std::string_view::npos)
          ++end;
        text.replace(start, end - start, numbers[at(std::size(numbers))]);
        break;
      }
      case 5:
        text.resize(i);
        break;
      default:
        text.insert(i, 1, char(random() & 0xff));
        break;
    }
  }
  return text;
}

// What the mutants came to: both must happen, or the mutations were idle.
struct outcomes {
  int loaded = 0, refused = 0;
  ~outcomes() {
    EXPECT_GT(loaded, 0);
    EXPECT_GT(refused, 0);
  }
};

// Loads `path`; a refusal must name the file, a loaded scene must hold
// finite positions.
void expect_loaded_or_refused(const std::string& path, const std::string& file_name, const std::string& mutant,
                              outcomes& seen) {
  scene s;
  load_report report;
  if (!load_scene(path, s, report)) {
    ++seen.refused;
    EXPECT_FALSE(report.error.empty()) << mutant;
    // One line, never the input echoed at length.
    EXPECT_EQ(report.error.find('\n'), std::string::npos) << report.error;
    EXPECT_LT(report.error.size(), 400u) << report.error;
    EXPECT_NE(report.error.find(file_name), std::string::npos) << report.error << "\n--- mutant:\n" << mutant;
    return;
  }
  ++seen.loaded;
  for (const surface& surf : s.surfaces) {
    const auto* mesh = std::get_if<polygon_mesh>(&surf.geometry);
    if (!mesh) continue;
    for (const vec3& p : mesh->positions) {
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << "\n--- mutant:\n" << mutant;
    }
  }
}

// Mutants of `seed` written to `file_name` in `dir`, each loaded; random
// stream `stream` (one per test, so each test's mutants stay the same).
void fuzz_scene_file(const scratch_dir& dir, const std::string& seed, const std::string& file_name,
                     std::uint64_t stream) {
  std::mt19937_64 random(stream);
  const bool binary = file_name.ends_with(".glb");
  outcomes seen;
  for (int i = 0; i < mutants_per_seed(); ++i) {
    const std::string mutant = mutate(seed, random);
    expect_loaded_or_refused(dir.write(file_name, mutant), file_name, binary ? "(binary)" : mutant, seen);
  }
}

const char* seed_obj =
    "# floor, wall, lamp, a textured triangle\n"
    "mtllib m.mtl\n"
    "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 2 -1\nv 1 2 -1\n"
    "v -0.3 1.9 -0.3\nv 0.3 1.9 -0.3\nv 0.3 1.9 0.3\nv -0.3 1.9 0.3\n"
    "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
    "g room\nusemtl white\nf 4 3 2 1\nf 1 2 6 5\n"
    "o lamp\nusemtl lamp\nf 7/1 8/2 9/3 10/1\n"
    "o tri\nusemtl tex\nf 1/1/1 2/2/1 3/3/1\nf -1 -2 -3\n";
const char* seed_mtl =
    "newmtl white\nKd 0.7 0.7 0.7\n"
    "newmtl lamp\nKd 0.5 0.5 0.5\nKe 5 5 5\n"
    "newmtl tex\nKd 0.6 0.6 0.6\nKs 0.2 0.2 0.2\nNs 20\nillum 2\nd 0.9\nNi 1.5\n";

TEST(ReaderFuzz, ObjFilesLoadOrAreRefusedByName) {
  scratch_dir dir;
  dir.write("m.mtl", seed_mtl);
  fuzz_scene_file(dir, seed_obj, "fuzz.obj", 1);
}

TEST(ReaderFuzz, MtlFilesLoadOrAreRefusedByName) {
  std::mt19937_64 random(2);
  scratch_dir dir;
  const std::string obj = dir.write("fuzz.obj", seed_obj);
  outcomes seen;
  for (int i = 0; i < mutants_per_seed(); ++i) {
    const std::string mutant = mutate(seed_mtl, random);
    dir.write("m.mtl", mutant);
    scene s;
    load_report report;
    ++(load_scene(obj, s, report) ? seen.loaded : seen.refused);
    if (!report.error.empty()) {
      EXPECT_NE(report.error.find("m.mtl"), std::string::npos) << report.error << "\n--- mutant:\n" << mutant;
    }
  }
}

TEST(ReaderFuzz, JsonScenesLoadOrAreRefusedByName) {
  const std::string seed = R"({
  "camera": {"eye": [0, 1, 4], "target": [0, 1, 0], "up": [0, 1, 0], "fov": 45, "size": [64, 48]},
  "sky": {"zenith": [1.2, 1.4, 2.0], "horizon": [0.9, 0.9, 0.9]},
  "textures": {"checks": {"checker": {"color0": [1, 1, 1], "color1": [0.1, 0.1, 0.1], "scale": 8}}},
  "materials": {
    "white": {"rho": [0.7, 0.7, 0.7]},
    "lamp": {"rho": [0.5, 0.5, 0.5], "ke": [5, 5, 5]},
    "glass": {"kr": [0.1, 0.1, 0.1], "kt": [0.85, 0.85, 0.85], "ior": 1.5, "fresnel": true},
    "floor": {"rho": [0.8, 0.8, 0.8], "texture": "checks"}
  },
  "lights": [{"position": [0, 1.5, 0], "intensity": [2, 2, 2]},
             {"type": "spot", "position": [0, 1.8, 0], "direction": [0, -1, 0], "intensity": [3, 3, 3],
              "inner_cone_degrees": 20, "outer_cone_degrees": 30}],
  "surfaces": [
    {"name": "floor", "polygon": [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]],
     "uv": [[0, 0], [0, 1], [1, 1], [1, 0]], "material": "floor"},
    {"name": "lamp", "polygon": [[-0.2, 1.9, -0.2], [0.2, 1.9, -0.2], [0.2, 1.9, 0.2], [-0.2, 1.9, 0.2]],
     "material": "lamp"},
    {"sphere": {"center": [0, 0.5, 0], "radius": 0.3}, "material": "glass"},
    {"quadric": {"a": 1, "c": 1, "k": -0.01, "box": [[-0.5, 0, -0.5], [0.5, 1, 0.5]]}, "material": "white"}
  ]
})";
  fuzz_scene_file(scratch_dir(), seed, "fuzz.json", 3);
}

// A lit quad with a material and a point light, as a glTF document.
test_support::gltf_file seed_gltf() {
  test_support::gltf_file f;
  const int position = f.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3);
  const int normal = f.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  const int uv = f.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 2);
  const int material = f.material(
      {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.6, 0.4, 1.0}}}}, {"emissiveFactor", {0.0, 0.0, 0.0}}});
  const int mesh = f.mesh({{{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uv}}},
                            {"indices", f.indices({0, 1, 2, 0, 2, 3})},
                            {"material", material}}});
  f.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  f.doc["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 5.0}}}}}}};
  const int quad = f.node({{"mesh", mesh}, {"translation", {0.0, 0.0, -1.0}}});
  const int light =
      f.node({{"translation", {0.5, 0.5, 1.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  f.roots({quad, light});
  return f;
}

TEST(ReaderFuzz, GltfFilesLoadOrAreRefusedByName) {
  fuzz_scene_file(scratch_dir(), seed_gltf().gltf_text(), "fuzz.gltf", 4);
}

TEST(ReaderFuzz, GlbFilesLoadOrAreRefusedByName) {
  fuzz_scene_file(scratch_dir(), seed_gltf().glb(), "fuzz.glb", 5);
}

TEST(ReaderFuzz, PfmFilesReadOrAreRefusedByName) {
  std::string seed = "PF\n3 2\n-1.0\n";
  for (int i = 0; i < 18; ++i) {
    const float v = 0.25f * float(i);
    seed.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  std::mt19937_64 random(6);
  scratch_dir dir;
  outcomes seen;
  for (int i = 0; i < mutants_per_seed(); ++i) {
    const std::string mutant = mutate(seed, random);
    image img;
    std::string error;
    if (read_pfm(dir.write("fuzz.pfm", mutant), img, error)) {
      ++seen.loaded;
      EXPECT_EQ(img.pixels.size(), std::size_t(3) * std::size_t(img.width) * std::size_t(img.height));
    } else {
      ++seen.refused;
      EXPECT_NE(error.find("fuzz.pfm"), std::string::npos) << error;
    }
  }
}

}  // namespace
}  // namespace bounce
