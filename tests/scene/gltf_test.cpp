// glTF 2.0 import: small .gltf (base64 data URIs) and .glb files written
// here, read through load_scene as `bounce x.gltf` reads them. Geometry and
// node transforms, base colour textures (linear texels, uv the right way
// up), emission, warnings for what is ignored, and bad files (each an error
// naming the file, never a crash).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <nlohmann/json.hpp>

#include "gltf_builder.h"
#include "image/image.h"
#include "measure/closed_forms.h"
#include "mesh_builders.h"
#include "radiosity/solver.h"
#include "scene/reader_support.h"
#include "scene/scene_io.h"
#include "scene/texture.h"
#include "test_files.h"
#include "trace/ray_scene.h"
#include "trace/ray_tracer.h"

namespace bounce {
namespace {

using json = nlohmann::json;
using test_support::base64;
using test_support::gltf_file;
using test_support::scratch_dir;

// A unit quad in the z = 0 plane facing +z, with uvs in glTF's convention
// (v = 0 at the image's top): corner (0, 1, 0) is the image's top left.
json unit_quad(gltf_file& f, int material, bool with_normals = true, bool with_uv = true) {
  json attributes = {{"POSITION", f.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3)}};
  if (with_normals) attributes["NORMAL"] = f.floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
  if (with_uv) attributes["TEXCOORD_0"] = f.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 2);
  json prim = {{"attributes", attributes}, {"indices", f.indices({0, 1, 2, 0, 2, 3})}};
  if (material >= 0) prim["material"] = material;
  return prim;
}

// A 2x2 PNG's bytes, `channels` per texel.
std::string png_2x2(const unsigned char* pixels, int channels) {
  std::string out;
  stbi_write_png_to_func(append_bytes, &out, 2, 2, channels, pixels, 2 * channels);
  return out;
}

// Top row red and green, bottom row blue and sRGB grey 128.
std::string png_2x2() {
  const unsigned char pixels[] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128};
  return png_2x2(pixels, 3);
}

bool load(const std::string& path, scene& s, load_report& report) {
  const bool ok = load_scene(path, s, report);
  EXPECT_TRUE(ok) << report.error;
  return ok;
}

std::string error_of(const std::string& path) {
  scene s;
  load_report report;
  EXPECT_FALSE(load_scene(path, s, report)) << path << " should fail";
  EXPECT_NE(report.error.find(path), std::string::npos) << "the error should name the file: " << report.error;
  return report.error;
}

const polygon_mesh& only_mesh(const scene& s) {
  EXPECT_EQ(s.surfaces.size(), 1u);
  return std::get<polygon_mesh>(s.surfaces.at(0).geometry);
}

// The uv at point p of the mesh (p must lie on one of its triangles).
std::optional<vec2> uv_at(const polygon_mesh& m, const vec3& p) {
  for (const polygon_face& f : m.faces) {
    const vec3 a = m.positions[f.position[0]], b = m.positions[f.position[1]], c = m.positions[f.position[2]];
    const vec3 n = glm::cross(b - a, c - a);
    const double area = glm::dot(n, n);
    const double wb = glm::dot(glm::cross(p - a, c - a), n) / area;
    const double wc = glm::dot(glm::cross(b - a, p - a), n) / area;
    if (wb >= -1e-12 && wc >= -1e-12 && wb + wc <= 1 + 1e-12)
      return (1 - wb - wc) * m.uvs[f.uv[0]] + wb * m.uvs[f.uv[1]] + wc * m.uvs[f.uv[2]];
  }
  return std::nullopt;
}

vec3 newell_normal(const polygon_mesh& m, const polygon_face& f) {
  vec3 n(0.0);
  for (std::size_t i = 0; i < f.position.size(); ++i)
    n += glm::cross(m.positions[f.position[i]], m.positions[f.position[(i + 1) % f.position.size()]]);
  return glm::normalize(n);
}

bool has_warning(const load_report& r, const std::string& text) {
  for (const std::string& w : r.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

int count_warnings(const load_report& r, const std::string& text) {
  int n = 0;
  for (const std::string& w : r.warnings) n += w.find(text) != std::string::npos;
  return n;
}

TEST(Gltf, TexturedQuadHasLinearTexelsAndUvTheRightWayUp) {
  scratch_dir dir;
  const std::string png = png_2x2();
  // The same quad three ways: image in the .glb's buffer, image as a data
  // URI, image as a file next to the .gltf.
  for (int form = 0; form < 3; ++form) {
    SCOPED_TRACE("form " + std::to_string(form));
    gltf_file f;
    json image;
    if (form == 0) image = {{"bufferView", f.view(png.data(), png.size())}, {"mimeType", "image/png"}};
    if (form == 1) image = {{"uri", "data:image/png;base64," + base64(png)}};
    if (form == 2) image = {{"uri", "checks.png"}};
    if (form == 2) dir.write("checks.png", png);
    f.doc["images"] = {image};
    f.doc["textures"] = {{{"source", 0}}};
    const int m = f.material(
        {{"pbrMetallicRoughness",
          {{"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}, {"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}}}});
    f.roots({f.node({{"mesh", f.mesh({unit_quad(f, m)})}})});
    const std::string path = form == 0 ? dir.write("quad.glb", f.glb()) : dir.write("quad.gltf", f.gltf_text());

    scene s;
    load_report report;
    ASSERT_TRUE(load(path, s, report));
    ASSERT_EQ(s.textures.size(), 1u);
    const texture& t = s.textures[0];
    EXPECT_EQ(t.kind, texture_kind::image);
    ASSERT_EQ(t.width, 2);
    ASSERT_EQ(t.height, 2);
    // sRGB 128 arrives linear: ((128/255 + 0.055) / 1.055)^2.4.
    const double grey = std::pow((128 / 255.0 + 0.055) / 1.055, 2.4);
    EXPECT_NEAR(t.texels[9], grey, 1e-6);
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].texture, 0);
    EXPECT_EQ(s.materials[0].rho, rgb(0.5));
    EXPECT_EQ(s.materials[0].ke, rgb(0.0));

    // Each quarter of the quad shows its texel: the top left red, the
    // bottom left blue (the image's top is the quad's +y side).
    const polygon_mesh& mesh = only_mesh(s);
    ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
    const std::pair<vec3, rgb> expected[] = {{{0.25, 0.75, 0}, {1, 0, 0}},
                                             {{0.75, 0.75, 0}, {0, 1, 0}},
                                             {{0.25, 0.25, 0}, {0, 0, 1}},
                                             {{0.75, 0.25, 0}, rgb(grey)}};
    for (const auto& [p, colour] : expected) {
      const auto uv = uv_at(mesh, p);
      ASSERT_TRUE(uv) << p.x << " " << p.y;
      const rgb value = texture_value(t, *uv);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(value[c], colour[c], 1e-6) << p.x << " " << p.y << " channel " << c;
    }
    // No emitter: the same warning a bare OBJ without one gets.
    EXPECT_TRUE(has_warning(report, path + ": no emitter")) << ::testing::PrintToString(report.warnings);
  }
}

// An emissive texture: the material emits its mean (the power), the glow
// follows the texture in the still, and a file lit only by glowing labels
// still opens under the automatic sky (a label is not a lamp).
TEST(Gltf, EmissiveTextureGlowsWhereTheTextureDoesWithItsMeanPower) {
  scratch_dir dir;
  gltf_file f;
  f.doc["images"] = {{{"uri", "data:image/png;base64," + base64(png_2x2())}}};
  f.doc["textures"] = {{{"source", 0}}};
  const int label = f.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0.0}}},
                                {"emissiveFactor", {2, 2, 2}},
                                {"emissiveTexture", {{"index", 0}}}});
  f.roots({f.node({{"mesh", f.mesh({unit_quad(f, label)})}})});
  const std::string path = dir.write("label.gltf", f.gltf_text());
  scene s;
  load_report report;
  ASSERT_TRUE(load(path, s, report));
  ASSERT_EQ(s.materials.size(), 1u);
  const double grey = std::pow((128 / 255.0 + 0.055) / 1.055, 2.4);
  const rgb mean = rgb(1.0 + grey) / 4.0;  // red, green, blue and grey texels
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.materials[0].ke[c], 2.0 * mean[c], 1e-6);
  EXPECT_EQ(s.materials[0].emission_texture, 0);
  EXPECT_TRUE(s.sky.on());
  EXPECT_TRUE(has_warning(report, path + ": no emitter: lit by a uniform white sky"))
      << ::testing::PrintToString(report.warnings);
  // Seen face on through the texel centres (a 2 x 2 still filling the
  // quad): each pixel glows with its texel x 2.
  s.view.eye = vec3(0.5, 0.5, 2.0);
  s.view.target = vec3(0.5, 0.5, 0.0);
  s.view.up = vec3(0, 1, 0);
  s.view.fov_y_degrees = 2.0 * std::atan(0.25) * 180.0 / std::numbers::pi;
  s.view.width = s.view.height = 2;
  s.sky = {};
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  const image still = trace_image(s, s.view, rays, nullptr, p);
  const rgb expected[2][2] = {{{2, 0, 0}, {0, 2, 0}}, {{0, 0, 2}, rgb(2 * grey)}};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(still.at(x, y)[c], expected[y][x][c], 1e-5) << x << "," << y;
}

// Khronos' ClearCoatTest (in Debian's assimp-testmodels): its labels have
// emissive textures. They glow, and the samples are lit by the automatic
// sky, not left black because the labels counted as lamps.
TEST(Gltf, ClearCoatTestOpensLitWithGlowingLabels) {
  const std::string path = "/usr/share/assimp/models/glTF2/ClearCoat-glTF/ClearCoatTest.gltf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "assimp-testmodels is not installed";
  scene s;
  load_report report;
  ASSERT_TRUE(load(path, s, report));
  EXPECT_TRUE(s.sky.on());
  int glowing = 0;
  for (const material& m : s.materials) glowing += m.emission_texture >= 0 && any_positive(m.ke);
  EXPECT_EQ(glowing, 1);  // LabelMaterial
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  p.light_samples = 64;
  auto mean_at = [&](const vec3& centre) {  // a small view straight at a point of the z = 0 plane
    camera c;
    c.eye = centre + vec3(0, 0, 10);
    c.target = centre;
    c.fov_y_degrees = 2.0;
    c.width = c.height = 8;
    const image still = trace_image(s, c, rays, nullptr, p);
    rgb sum(0.0);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) sum += rgb(still.at(x, y)) / 64.0;
    return sum;
  };
  // The top-left sample (base layer, simple coating), at (-2.1, 5.25):
  // red, lit by the sky. Measured (0.495, 0.020, 0.010): rho (0.5, 0.02,
  // 0.01) under a sky of radiance 1, a little of it hidden.
  const rgb sample = mean_at(vec3(-2.1, 5.25, 0.0));
  EXPECT_GT(sample.r, 0.4);
  EXPECT_GT(sample.r, 5.0 * sample.g);
  // Its label above it, at (-2.09, 6.62): white around black letters
  // (measured 0.80 grey).
  const rgb label = mean_at(vec3(-2.087, 6.616, 0.0));
  EXPECT_GT(channel_mean(label), 0.3) << label.r;
}

TEST(Gltf, EmissiveQuadGetsFactorTimesStrength) {
  scratch_dir dir;
  gltf_file f;
  f.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  const int light =
      f.material({{"name", "lamp"},
                  {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.3, 0.4, 1}}, {"metallicFactor", 0}}},
                  {"emissiveFactor", {1.0, 0.5, 0.25}},
                  {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}});
  // glTF's default material colour is white: clamped as OBJ's Kd 1 is.
  const int white = f.material({{"name", "white"}, {"pbrMetallicRoughness", {{"metallicFactor", 0}}}});
  const int quad_light = f.mesh({unit_quad(f, light, true, false)});
  const int quad_white = f.mesh({unit_quad(f, white, true, false)});
  f.roots({f.node({{"mesh", quad_light}, {"translation", {0, 0, 1}}, {"rotation", {1, 0, 0, 0}}}),
           f.node({{"mesh", quad_white}})});
  const std::string path = dir.write("lamp.gltf", f.gltf_text());
  scene s;
  load_report report;
  ASSERT_TRUE(load(path, s, report));
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].name, "lamp");
  EXPECT_EQ(s.materials[0].ke, rgb(4.0, 2.0, 1.0));
  EXPECT_EQ(s.materials[0].rho, rgb(0.2, 0.3, 0.4));
  EXPECT_EQ(s.materials[1].rho, rgb(max_reflectance));
  EXPECT_TRUE(has_warning(report, "materials[1] 'white': baseColorFactor channels of 1 or more clamped to 0.99"))
      << ::testing::PrintToString(report.warnings);
  EXPECT_FALSE(has_warning(report, "no emitter"));
  EXPECT_FALSE(has_warning(report, "KHR_materials_emissive_strength"));  // supported, not warned about
  EXPECT_FALSE(has_warning(report, "metallic"));                         // metallicFactor 0
}

TEST(Gltf, ChildLandsWhereTheComposedTransformPutsIt) {
  scratch_dir dir;
  gltf_file f;
  const int m = f.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}});
  // A triangle tilted out of the z = 0 plane, normal along (0, -1, 1).
  const double r = std::sqrt(0.5);
  json prim = {
      {"attributes",
       {{"POSITION", f.floats({0, 0, 0, 1, 0, 0, 0, 1, 1}, "VEC3", 3)},
        {"NORMAL", f.floats({0, float(-r), float(r), 0, float(-r), float(r), 0, float(-r), float(r)}, "VEC3", 3)}}},
      {"material", m}};
  const int tri = f.mesh({prim});
  // Child: translated by (1, 0, 0) and stretched by 2 along y; parent:
  // scaled by 2, turned 90 degrees about z, moved to (10, 0, 0).
  const int child = f.node({{"mesh", tri}, {"translation", {1, 0, 0}}, {"scale", {1, 2, 1}}});
  const double h = std::sqrt(0.5);
  f.node({{"children", {child}}, {"translation", {10, 0, 0}}, {"rotation", {0, 0, h, h}}, {"scale", {2, 2, 2}}});
  f.roots({1});
  const std::string path = dir.write("tree.gltf", f.gltf_text());
  scene s;
  load_report report;
  ASSERT_TRUE(load(path, s, report));
  const polygon_mesh& mesh = only_mesh(s);
  ASSERT_EQ(mesh.positions.size(), 3u);
  // Corner by corner: child (x + 1, 2y, z), parent scale 2, then
  // (x, y) -> (-y, x), then + (10, 0, 0).
  const vec3 expected[] = {{10, 2, 0}, {10, 4, 0}, {6, 2, 2}};
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mesh.positions[i][c], expected[i][c], 1e-6) << "corner " << i;
  // Normals go by the inverse transpose: they stay perpendicular to the
  // transformed triangle (a plain transform would tilt them).
  ASSERT_EQ(mesh.normals.size(), 3u);
  const vec3 face = newell_normal(mesh, mesh.faces[0]);
  for (const vec3& n : mesh.normals) EXPECT_NEAR(glm::dot(n, face), 1.0, 1e-6);

  // The same parent as a matrix (column-major) gives the same corners.
  f.doc["nodes"][1].erase("translation");
  f.doc["nodes"][1].erase("rotation");
  f.doc["nodes"][1].erase("scale");
  f.doc["nodes"][1]["matrix"] = {0, 2, 0, 0, -2, 0, 0, 0, 0, 0, 2, 0, 10, 0, 0, 1};
  scene s2;
  ASSERT_TRUE(load(dir.write("tree_matrix.gltf", f.gltf_text()), s2, report));
  const polygon_mesh& mesh2 = only_mesh(s2);
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mesh2.positions[i][c], expected[i][c], 1e-6) << "corner " << i;
}

TEST(Gltf, MirroredNodeKeepsFacesAndNormalsOutward) {
  scratch_dir dir;
  gltf_file f;
  const int m = f.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}});
  // A tetrahedron, faces anticlockwise seen from outside, with flat normals.
  const vec3 v[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::vector<float> positions, normals;
  for (const auto& face : faces) {
    const vec3 n = glm::normalize(glm::cross(v[face[1]] - v[face[0]], v[face[2]] - v[face[0]]));
    for (int i : face)
      for (int c = 0; c < 3; ++c) {
        positions.push_back(float(v[i][c]));
        normals.push_back(float(n[c]));
      }
  }
  const int tet =
      f.mesh({{{"attributes", {{"POSITION", f.floats(positions, "VEC3", 3)}, {"NORMAL", f.floats(normals, "VEC3", 3)}}},
               {"material", m}}});
  f.roots({f.node({{"mesh", tet}, {"scale", {-1, 1, 1}}, {"translation", {5, 0, 0}}})});
  const std::string path = dir.write("mirror.gltf", f.gltf_text());
  scene s;
  load_report report;
  ASSERT_TRUE(load(path, s, report));
  const polygon_mesh& mesh = only_mesh(s);
  ASSERT_EQ(mesh.faces.size(), 4u);
  vec3 centre(0.0);
  for (const vec3& p : mesh.positions) centre += p / double(mesh.positions.size());
  EXPECT_NEAR(centre.x, 5 - 0.25, 1e-6);
  for (const polygon_face& face : mesh.faces) {
    vec3 mid(0.0);
    for (int i : face.position) mid += mesh.positions[i] / 3.0;
    const vec3 n = newell_normal(mesh, face);
    EXPECT_GT(glm::dot(n, mid - centre), 0.0) << "a face turned inward";
    ASSERT_EQ(face.normal.size(), 3u);
    for (int i : face.normal) EXPECT_NEAR(glm::dot(mesh.normals[i], n), 1.0, 1e-6);
  }
}

// Metallic-roughness: a smooth metal is a mirror of its base colour, a
// half-metal part mirror and part diffuse; rough metals and smooth
// plastics stay diffuse (the thresholds: gltf_io.h).
TEST(Gltf, SmoothMetalIsAMirrorAndRoughMetalStaysDiffuse) {
  scratch_dir dir;
  gltf_file f;
  auto pbr = [&](double metallic, double roughness, double r, double g, double b) {
    return f.material(
        {{"pbrMetallicRoughness",
          {{"baseColorFactor", {r, g, b, 1}}, {"metallicFactor", metallic}, {"roughnessFactor", roughness}}}});
  };
  const int gold = pbr(1.0, 0.1, 0.9, 0.6, 0.2), half = pbr(0.6, 0.25, 0.5, 0.5, 0.5),
            brushed = pbr(1.0, 0.6, 0.7, 0.7, 0.7), plastic = pbr(0.0, 0.0, 0.2, 0.4, 0.6);
  const int mesh = f.mesh({unit_quad(f, gold), unit_quad(f, half), unit_quad(f, brushed), unit_quad(f, plastic)});
  f.roots({f.node({{"mesh", mesh}})});
  const std::string path = dir.write("metals.gltf", f.gltf_text());
  scene s;
  load_report report;
  ASSERT_TRUE(load(path, s, report));
  ASSERT_EQ(s.materials.size(), 4u);
  EXPECT_EQ(s.materials[0].kr, rgb(0.9, 0.6, 0.2));
  EXPECT_EQ(s.materials[0].rho, rgb(0.0));
  EXPECT_NEAR(s.materials[1].kr.r, 0.3, 1e-12);
  EXPECT_NEAR(s.materials[1].rho.r, 0.2, 1e-12);
  EXPECT_EQ(s.materials[2].kr, rgb(0.0));
  EXPECT_EQ(s.materials[2].rho, rgb(0.7));
  EXPECT_EQ(s.materials[3].kr, rgb(0.0));
  EXPECT_EQ(s.materials[3].rho, rgb(0.2, 0.4, 0.6));
  EXPECT_EQ(count_warnings(report, "metallic and roughness ignored for rough metals"), 1)
      << ::testing::PrintToString(report.warnings);
}

// KHR_materials_transmission: glass. Thin-walled without a volume (light
// goes straight through, the interface's reflection at normal incidence);
// a solid that refracts at KHR_materials_ior's index with one.
TEST(Gltf, TransmissionIsGlassThinOrSolid) {
  scratch_dir dir;
  gltf_file f;
  f.doc["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"};
  auto glass = [&](double transmission, const json& more) {
    json ext = {{"KHR_materials_transmission", {{"transmissionFactor", transmission}}}};
    for (auto& [k, v] : more.items()) ext[k] = v;
    return f.material({{"pbrMetallicRoughness",
                        {{"baseColorFactor", {0.9, 0.9, 0.8, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.0}}},
                       {"extensions", ext}});
  };
  const int window = glass(1.0, json::object());
  const int water =
      glass(1.0, {{"KHR_materials_ior", {{"ior", 1.33}}}, {"KHR_materials_volume", {{"thicknessFactor", 1.0}}}});
  const int frosted = glass(0.5, {{"KHR_materials_volume", {{"thicknessFactor", 0.1}}}});
  const int mesh = f.mesh({unit_quad(f, window), unit_quad(f, water), unit_quad(f, frosted)});
  f.roots({f.node({{"mesh", mesh}})});
  const std::string path = dir.write("glass.gltf", f.gltf_text());
  scene s;
  load_report report;
  ASSERT_TRUE(load(path, s, report));
  ASSERT_EQ(s.materials.size(), 3u);
  const double r0 = 0.04;  // ((1.5 - 1) / (1.5 + 1))^2
  EXPECT_EQ(s.materials[0].rho, rgb(0.0));
  EXPECT_NEAR(s.materials[0].kt.r, 0.9 * (1 - r0), 1e-12);
  EXPECT_NEAR(s.materials[0].kr.b, 0.8 * r0, 1e-12);
  EXPECT_EQ(s.materials[0].ior, 1.0);
  EXPECT_FALSE(s.materials[0].fresnel);
  EXPECT_NEAR(s.materials[1].kt.g, 0.9, 1e-12);
  EXPECT_EQ(s.materials[1].kr, rgb(0.0));
  EXPECT_EQ(s.materials[1].ior, 1.33);
  EXPECT_TRUE(s.materials[1].fresnel);
  EXPECT_NEAR(s.materials[2].rho.r, 0.45, 1e-12);
  EXPECT_NEAR(s.materials[2].kt.r, 0.45, 1e-12);
  EXPECT_EQ(s.materials[2].ior, 1.5);
  EXPECT_EQ(count_warnings(report, "not supported"), 0) << ::testing::PrintToString(report.warnings);
  // An index out of its range is named.
  f.doc["materials"][1]["extensions"]["KHR_materials_ior"]["ior"] = 0.5;
  EXPECT_NE(error_of(dir.write("bad.gltf", f.gltf_text())).find("materials[1]: ior must be a number from 1 to 10"),
            std::string::npos);
}

TEST(Gltf, IgnoredFeaturesAreWarnedAboutOncePerKind) {
  scratch_dir dir;
  gltf_file f;
  f.doc["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_lights_punctual"};
  f.doc["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}}}}}}};
  f.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
  f.doc["images"] = {{{"uri", "data:image/png;base64," + base64(png_2x2())}}};
  f.doc["textures"] = {{{"source", 0}}};
  // Two metallic materials with normal maps, and a line primitive.
  const int a = f.material({{"normalTexture", {{"index", 0}}}, {"emissiveFactor", {1, 1, 1}}});
  const int b = f.material({{"normalTexture", {{"index", 0}}}});
  json lines = {{"attributes", {{"POSITION", f.floats({0, 0, 0, 1, 0, 0}, "VEC3", 3)}}}, {"mode", 1}};
  const int mesh = f.mesh({unit_quad(f, a), unit_quad(f, b), lines});
  f.roots({f.node({{"mesh", mesh}, {"camera", 0}})});
  const std::string path = dir.write("extras.gltf", f.gltf_text());
  scene s;
  load_report report;
  ASSERT_TRUE(load(path, s, report));
  const std::string all = ::testing::PrintToString(report.warnings);
  EXPECT_EQ(count_warnings(report, "metallic and roughness ignored"), 1) << all;
  EXPECT_EQ(count_warnings(report, "normal maps ignored"), 1) << all;
  EXPECT_EQ(count_warnings(report, "cameras ignored"), 1) << all;
  EXPECT_EQ(count_warnings(report, "KHR_lights_punctual"), 0) << all;  // read; this one is on no node
  EXPECT_TRUE(s.lights.empty());
  EXPECT_EQ(count_warnings(report, "'KHR_materials_clearcoat' is not supported"), 1) << all;
  EXPECT_EQ(count_warnings(report, "points and lines have no area"), 1) << all;
  for (const std::string& w : report.warnings) EXPECT_EQ(w.rfind(path + ": ", 0), 0u) << w;
  std::size_t faces = 0;
  for (const surface& surf : s.surfaces) faces += std::get<polygon_mesh>(surf.geometry).faces.size();
  EXPECT_EQ(faces, 4u);
}

// KHR_lights_punctual: a light shines down its node's -Z, from the node's
// origin; candela and lux are kept as they are (docs/scene-format.md).
TEST(Gltf, PunctualLightsArePlacedByTheirNodes) {
  scratch_dir dir;
  gltf_file f;
  f.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  f.doc["extensions"] = {
      {"KHR_lights_punctual",
       {{"lights",
         {{{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 100.0}, {"range", 5.0}},
          {{"type", "spot"}, {"intensity", 50.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
          {{"type", "directional"}, {"intensity", 3.0}}}}}}};
  const int m = f.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}});
  const int quad = f.node({{"mesh", f.mesh({unit_quad(f, m)})}});
  const double h = std::sqrt(0.5);
  const json lamp = {{"KHR_lights_punctual", {{"light", 0}}}};
  const int point = f.node({{"translation", {0, 3, 0}}, {"extensions", lamp}});
  // Turned -90 degrees about x: -Z becomes -Y, straight down.
  const int spot = f.node({{"translation", {1, 2, 0}},
                           {"rotation", {-h, 0, 0, h}},
                           {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  // A sun under a scaled parent: the direction stays a unit vector.
  const int sun = f.node({{"rotation", {-h, 0, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  const int parent = f.node({{"children", {sun}}, {"scale", {2, 2, 2}}});
  f.roots({quad, point, spot, parent});
  const std::string path = dir.write("lamps.gltf", f.gltf_text());
  scene s;
  load_report report;
  ASSERT_TRUE(load(path, s, report));
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lights[0].type, light_type::point);
  EXPECT_EQ(s.lights[0].position, vec3(0, 3, 0));
  EXPECT_EQ(s.lights[0].intensity, rgb(100, 50, 25));
  EXPECT_EQ(s.lights[1].type, light_type::spot);
  EXPECT_EQ(s.lights[1].position, vec3(1, 2, 0));
  EXPECT_NEAR(glm::length(s.lights[1].direction - vec3(0, -1, 0)), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.lights[1].inner_cone, 0.2);
  EXPECT_DOUBLE_EQ(s.lights[1].outer_cone, 0.5);
  EXPECT_EQ(s.lights[1].intensity, rgb(50.0));
  EXPECT_EQ(s.lights[2].type, light_type::sun);
  EXPECT_NEAR(glm::length(s.lights[2].direction - vec3(0, -1, 0)), 0.0, 1e-12);
  EXPECT_EQ(s.lights[2].intensity, rgb(3.0));
  // Lights of its own: no automatic sky.
  EXPECT_FALSE(s.sky.on());
  EXPECT_EQ(count_warnings(report, "range ignored"), 1) << ::testing::PrintToString(report.warnings);
  EXPECT_EQ(count_warnings(report, "white sky"), 0);

  // Broken lights are named.
  gltf_file bad = f;
  bad.doc["nodes"][point]["extensions"]["KHR_lights_punctual"]["light"] = 7;
  EXPECT_NE(error_of(dir.write("index.gltf", bad.gltf_text()))
                .find("nodes[1].extensions.KHR_lights_punctual.light: light 7 does not exist (the file has 3)"),
            std::string::npos);
  bad = f;
  bad.doc["extensions"]["KHR_lights_punctual"]["lights"][1]["spot"]["innerConeAngle"] = 0.6;
  EXPECT_NE(error_of(dir.write("cone.gltf", bad.gltf_text())).find("KHR_lights_punctual.lights[1]: spot cone"),
            std::string::npos);
  bad = f;
  bad.doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = -1;
  EXPECT_NE(error_of(dir.write("negative.gltf", bad.gltf_text())).find("lights[0]: color and intensity"),
            std::string::npos);
}

// KHR_draco_mesh_compression: the primitive's geometry comes from the Draco
// stream (here written by libdraco's own encoder, positions quantised to 14
// bits), not from its accessors, which have no bufferView.
TEST(Gltf, DracoCompressedMeshesAreDecoded) {
  const std::array<float, 3> corners[4] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  const std::array<float, 2> uvs[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  const int faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(2);
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int tex = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
  for (int f = 0; f < 2; ++f) {
    const int* v = faces[f];
    builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), corners[v[0]].data(), corners[v[1]].data(),
                                      corners[v[2]].data());
    builder.SetAttributeValuesForFace(tex, draco::FaceIndex(f), uvs[v[0]].data(), uvs[v[1]].data(), uvs[v[2]].data());
  }
  std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  ASSERT_TRUE(mesh);
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
  draco::EncoderBuffer encoded;
  ASSERT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &encoded).ok());

  gltf_file f;
  f.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  f.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  const int view = f.view(encoded.data(), encoded.size());
  auto accessor = [&](const char* type, int component, int count) {
    f.doc["accessors"].push_back({{"componentType", component}, {"count", count}, {"type", type}});
    return int(f.doc["accessors"].size()) - 1;
  };
  const int position = accessor("VEC3", 5126, int(mesh->num_points()));
  f.doc["accessors"][position]["min"] = {0, 0, 0};
  f.doc["accessors"][position]["max"] = {2, 1, 0};
  const json prim = {
      {"attributes", {{"POSITION", position}, {"TEXCOORD_0", accessor("VEC2", 5126, int(mesh->num_points()))}}},
      {"indices", accessor("SCALAR", 5125, 6)},
      {"extensions",
       {{"KHR_draco_mesh_compression",
         {{"bufferView", view},
          {"attributes",
           {{"POSITION", mesh->attribute(pos)->unique_id()}, {"TEXCOORD_0", mesh->attribute(tex)->unique_id()}}}}}}}};
  f.doc["images"] = {{{"uri", "data:image/png;base64," + base64(png_2x2())}}};
  f.doc["textures"] = {{{"source", 0}}};
  json with_material = prim;
  with_material["material"] = f.material(
      {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}, {"baseColorTexture", {{"index", 0}}}}}});
  f.roots({f.node({{"mesh", f.mesh({with_material})}})});
  scratch_dir dir;
  for (const std::string name : {"draco.gltf", "draco.glb"}) {
    const std::string path = dir.write(name, name.ends_with(".glb") ? f.glb() : f.gltf_text());
    scene s;
    load_report report;
    ASSERT_TRUE(load(path, s, report)) << name;
    const polygon_mesh& m = only_mesh(s);
    ASSERT_EQ(m.faces.size(), 2u) << name;
    double area = 0.0;
    for (const polygon_face& face : m.faces) {
      const vec3 a = m.positions[std::size_t(face.position[0])], b = m.positions[std::size_t(face.position[1])],
                 c = m.positions[std::size_t(face.position[2])];
      area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    EXPECT_NEAR(area, 2.0, 1e-3) << name;  // 14-bit positions over a range of 2
    // uv (1, 0) in glTF is the image's bottom right: Bounce's (1, 1) is at corner (2, 1).
    const auto uv = uv_at(m, vec3(2, 1, 0));
    ASSERT_TRUE(uv) << name;
    EXPECT_NEAR(uv->x, 1.0, 1.0 / 4096);  // texture coordinates quantised to 12 bits
    EXPECT_NEAR(uv->y, 1.0, 1.0 / 4096);
    EXPECT_EQ(count_warnings(report, "not supported"), 0) << ::testing::PrintToString(report.warnings);
  }
  // A stream that is not Draco is named.
  gltf_file bad = f;
  bad.bin.replace(0, 8, "notdraco");
  EXPECT_NE(error_of(dir.write("bad.gltf", bad.gltf_text())).find("KHR_draco_mesh_compression: not a Draco stream"),
            std::string::npos);
}

// The Khronos sample 2CylinderEngine, Draco-compressed (assimp-testmodels):
// every primitive decodes to the triangles its index accessor counts.
TEST(Gltf, DracoCompressedSampleOpensWhole) {
  const std::string path = "/usr/share/assimp/models/glTF2/draco/2CylinderEngine.gltf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const json doc = json::parse(test_support::read_text(path));
  std::size_t expected = 0;
  for (const json& node : doc["nodes"])
    if (node.contains("mesh"))
      for (const json& prim : doc["meshes"][node["mesh"].get<std::size_t>()]["primitives"])
        expected += doc["accessors"][prim["indices"].get<std::size_t>()]["count"].get<std::size_t>() / 3;
  scene s;
  load_report report;
  ASSERT_TRUE(load(path, s, report));
  std::size_t faces = 0;
  for (const surface& surf : s.surfaces) faces += std::get<polygon_mesh>(surf.geometry).faces.size();
  EXPECT_EQ(faces + report.dropped_faces, expected);
  std::printf("2CylinderEngine: %zu triangles, %zu degenerate dropped\n", faces, std::size_t(report.dropped_faces));
}

// A 2x2 RGBA PNG: white, the left column opaque, the right one clear.
std::string png_half_clear() {
  const unsigned char pixels[] = {255, 255, 255, 255, 255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 0};
  return png_2x2(pixels, 4);
}

// alphaMode MASK: a cut-out. The still sees through its holes (camera and
// shadow rays alike); the alpha stays linear.
TEST(Gltf, AlphaMaskIsACutOutInTheStill) {
  scratch_dir dir;
  gltf_file f;
  f.doc["images"] = {{{"uri", "data:image/png;base64," + base64(png_half_clear())}}};
  f.doc["textures"] = {{{"source", 0}}};
  const int leaf =
      f.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}}},
                  {"emissiveFactor", {1, 1, 1}},
                  {"alphaMode", "MASK"},
                  {"alphaCutoff", 0.5}});
  const int wall =
      f.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}}}, {"emissiveFactor", {0, 0, 1}}});
  const int front = f.node({{"mesh", f.mesh({unit_quad(f, leaf)})}});
  const int back = f.node({{"mesh", f.mesh({unit_quad(f, wall)})}, {"translation", {0, 0, -1}}, {"scale", {1, 1, 1}}});
  f.roots({front, back});
  const std::string path = dir.write("leaf.gltf", f.gltf_text());
  scene s;
  load_report report;
  ASSERT_TRUE(load(path, s, report));
  ASSERT_EQ(s.textures.size(), 1u);
  ASSERT_EQ(s.textures[0].alpha.size(), 4u);
  EXPECT_EQ(s.textures[0].alpha[0], 1.0f);
  EXPECT_EQ(s.textures[0].alpha[1], 0.0f);
  const material& m = s.materials[std::size_t(std::get<polygon_mesh>(s.surfaces[0].geometry).faces[0].material)];
  EXPECT_EQ(m.alpha_cutoff, 0.5);
  EXPECT_EQ(count_warnings(report, "alphaMode"), 0);
  // Face on, through the texel centres: the left column shows the leaf,
  // the right one the wall behind it. Seen from the front (camera at +z).
  s.view.eye = vec3(0.5, 0.5, 3.0);
  s.view.target = vec3(0.5, 0.5, 0.0);
  s.view.up = vec3(0, 1, 0);
  s.view.fov_y_degrees = 2.0 * std::atan(0.5 / 3.0) * 180.0 / std::numbers::pi;
  s.view.width = s.view.height = 2;
  s.sky = {};
  const ray_scene rays(s);
  trace_params p;
  p.diffuse = diffuse_source::ambient;
  const image still = trace_image(s, s.view, rays, nullptr, p);
  for (int y = 0; y < 2; ++y) {
    EXPECT_NEAR(still.at(0, y).r, 1.0, 1e-5) << y;  // the leaf
    EXPECT_NEAR(still.at(1, y).r, 0.0, 1e-5) << y;  // through the hole: the blue wall
    EXPECT_NEAR(still.at(1, y).b, 1.0, 1e-5) << y;
  }
  // A shadow ray through the hole is not blocked; through the leaf it is.
  EXPECT_FALSE(rays.occluded(vec3(0.75, 0.5, 1.0), vec3(0.75, 0.5, -0.5)));
  EXPECT_TRUE(rays.occluded(vec3(0.25, 0.5, 1.0), vec3(0.25, 0.5, -0.5)));
}

// ---- bad files -----------------------------------------------------------

// A valid one-quad file to break in one place.
gltf_file good_quad() {
  gltf_file f;
  const int m = f.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}});
  f.roots({f.node({{"mesh", f.mesh({unit_quad(f, m)})}})});
  return f;
}

TEST(Gltf, MissingAndNonGltfFiles) {
  scratch_dir dir;
  error_of(dir.path("nothere.gltf"));
  error_of(dir.path("nothere.glb"));
  EXPECT_NE(error_of(dir.write("text.gltf", "this is not JSON")).find("text.gltf: "), std::string::npos);
  error_of(dir.write("array.gltf", "[1, 2, 3]"));
  const std::string e = error_of(dir.write("cut.gltf", R"({"asset": {"version": "2.0"}, "meshes": [)"));
  EXPECT_NE(e.find("cut.gltf: invalid JSON: parse error at line 1"), std::string::npos) << e;
  error_of(dir.write("noasset.gltf", R"({"meshes": []})"));
  error_of(dir.write("empty.glb", ""));
  // A missing external buffer.
  gltf_file f = good_quad();
  json d = json::parse(f.gltf_text());
  d["buffers"][0]["uri"] = "missing.bin";
  EXPECT_NE(error_of(dir.write("nobin.gltf", d.dump())).find("missing.bin"), std::string::npos);
  // A base colour image that is not there, or not an image (as map_Kd).
  for (const std::string& uri : {std::string("nothere.png"), "data:image/png;base64," + base64("not a png")}) {
    gltf_file t;
    t.doc["images"] = {{{"uri", uri}}};
    t.doc["textures"] = {{{"source", 0}}};
    const int m = t.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
    t.roots({t.node({{"mesh", t.mesh({unit_quad(t, m)})}})});
    const std::string e = error_of(dir.write("image.gltf", t.gltf_text()));
    EXPECT_NE(e.find("image.gltf: images[0]: cannot"), std::string::npos) << e;
  }
}

TEST(Gltf, TruncatedGlb) {
  scratch_dir dir;
  const std::string glb = good_quad().glb();
  scene s;
  load_report report;
  ASSERT_TRUE(load(dir.write("whole.glb", glb), s, report));
  for (std::size_t keep : {std::size_t(10), std::size_t(30), glb.size() / 2, glb.size() - 4}) {
    const std::string e = error_of(dir.write("cut" + std::to_string(keep) + ".glb", glb.substr(0, keep)));
    EXPECT_NE(e.find("truncated"), std::string::npos) << e;
  }
}

// A glTF 1.0 .gltf said "no triangles in the scene"; the .glb path already
// named the version. An embedded buffer that is too short was quoted whole
// (a megabyte of base64): messages keep its start and its length.
TEST(Gltf, OldVersionsAndShortEmbeddedBuffersAreNamedBriefly) {
  scratch_dir dir;
  gltf_file old = good_quad();
  old.doc["asset"]["version"] = "1.0";
  EXPECT_NE(error_of(dir.write("old.gltf", old.gltf_text())).find("glTF version 1.0; Bounce reads version 2"),
            std::string::npos);
  gltf_file shortened = good_quad();
  shortened.bin += std::string(100000, '\0');  // 133 KB of base64
  std::string text = shortened.gltf_text();
  // The buffer claims 8 bytes more than its data URI holds.
  const std::string claim = "\"byteLength\":" + std::to_string(shortened.bin.size());
  text.replace(text.find(claim), claim.size(), "\"byteLength\":" + std::to_string(shortened.bin.size() + 8));
  const std::string e = error_of(dir.write("short.gltf", text));
  EXPECT_LT(e.size(), 400u) << e.substr(0, 400);
}

TEST(Gltf, BadAccessorsAndIndicesNameMeshPrimitiveAndAccessor) {
  scratch_dir dir;
  {  // POSITION names an accessor that does not exist
    gltf_file f = good_quad();
    f.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99;
    const std::string e = error_of(dir.write("accessor.gltf", f.gltf_text()));
    EXPECT_NE(e.find("meshes[0].primitives[0].attributes.POSITION: accessor 99 does not exist"), std::string::npos)
        << e;
  }
  {  // an accessor reading past its buffer view
    gltf_file f = good_quad();
    f.doc["accessors"][0]["count"] = 40;
    const std::string e = error_of(dir.write("range.gltf", f.gltf_text()));
    EXPECT_NE(e.find("meshes[0].primitives[0].attributes.POSITION (accessor 0)"), std::string::npos) << e;
  }
  {  // a buffer view past the end of its buffer
    gltf_file f = good_quad();
    f.doc["bufferViews"][0]["byteOffset"] = 1000;
    const std::string e = error_of(dir.write("view.glb", f.glb()));
    EXPECT_NE(e.find("bufferViews[0]"), std::string::npos) << e;
  }
  {  // a buffer view naming a buffer that does not exist
    gltf_file f = good_quad();
    f.doc["bufferViews"][1]["buffer"] = 3;
    const std::string e = error_of(dir.write("buffer.gltf", f.gltf_text()));
    EXPECT_NE(e.find("buffer 3 does not exist"), std::string::npos) << e;
  }
  {  // an index beyond the vertices
    gltf_file f;
    const int m = f.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}});
    json prim = {{"attributes", {{"POSITION", f.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3)}}},
                 {"indices", f.indices({0, 1, 2, 0, 2, 7})},
                 {"material", m}};
    f.roots({f.node({{"mesh", f.mesh({prim})}})});
    const std::string e = error_of(dir.write("index.gltf", f.gltf_text()));
    EXPECT_NE(e.find("meshes[0].primitives[0].indices (accessor 1): element 5 is vertex 7, out of range (4 vertices)"),
              std::string::npos)
        << e;
  }
  {  // indices naming an accessor that does not exist (tinygltf checks this one)
    gltf_file f = good_quad();
    f.doc["meshes"][0]["primitives"][0]["indices"] = 42;
    error_of(dir.write("indices.gltf", f.gltf_text()));
  }
  {  // mesh, material and node indices out of range, a cycle of nodes
    gltf_file f = good_quad();
    f.doc["nodes"][0]["mesh"] = 5;
    EXPECT_NE(error_of(dir.write("mesh.gltf", f.gltf_text())).find("mesh 5 does not exist"), std::string::npos);
    f = good_quad();
    f.doc["meshes"][0]["primitives"][0]["material"] = 8;
    EXPECT_NE(error_of(dir.write("material.gltf", f.gltf_text())).find("material 8 does not exist"), std::string::npos);
    f = good_quad();
    f.doc["nodes"][0]["children"] = {0};
    EXPECT_NE(error_of(dir.write("cycle.gltf", f.gltf_text())).find("cycle"), std::string::npos);
  }
}

TEST(Gltf, NanPositionsAndDegenerateGeometryAreErrors) {
  scratch_dir dir;
  gltf_file f;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  f.roots({f.node(
      {{"mesh", f.mesh({{{"attributes", {{"POSITION", f.floats({0, 0, 0, 1, nan, 0, 0, 1, 0}, "VEC3", 3)}}}}})}})});
  std::string e = error_of(dir.write("nan.glb", f.glb()));
  EXPECT_NE(e.find("meshes[0].primitives[0].attributes.POSITION (accessor 0): element 1 is not a finite number"),
            std::string::npos)
      << e;
  // Every triangle degenerate: nothing left to light.
  gltf_file g;
  g.roots({g.node(
      {{"mesh", g.mesh({{{"attributes", {{"POSITION", g.floats({0, 0, 0, 1, 1, 1, 2, 2, 2}, "VEC3", 3)}}}}})}})});
  e = error_of(dir.write("flat.gltf", g.gltf_text()));
  EXPECT_NE(e.find("no surfaces left"), std::string::npos) << e;
  // Only lines: no triangles at all.
  gltf_file l;
  l.roots({l.node(
      {{"mesh", l.mesh({{{"attributes", {{"POSITION", l.floats({0, 0, 0, 1, 1, 1}, "VEC3", 3)}}}, {"mode", 1}}})}})});
  e = error_of(dir.write("lines.gltf", l.gltf_text()));
  EXPECT_NE(e.find("no triangles"), std::string::npos) << e;
}

// The loaded scene solves: an emissive glTF quad 1 above a diffuse one
// sends rho x F x (pi ke) into it, F the closed form for facing squares.
TEST(Gltf, EmissiveQuadLightsTheQuadBelow) {
  scratch_dir dir;
  gltf_file f;
  const int light = f.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0}}},
                                {"emissiveFactor", {1, 1, 1}}});
  const int grey =
      f.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}, {"metallicFactor", 0}}}});
  // The lamp turned over (180 degrees about x) to face down at z = 1.
  f.roots({f.node({{"mesh", f.mesh({unit_quad(f, light, false, false)})},
                   {"translation", {0, 1, 1}},
                   {"rotation", {1, 0, 0, 0}}}),
           f.node({{"mesh", f.mesh({unit_quad(f, grey, false, false)})}})});
  scene s;
  load_report report;
  ASSERT_TRUE(load(dir.write("lit.glb", f.glb()), s, report));
  const patch_mesh mesh = test_support::mesh_of(s, 0.2);
  radiosity_params params;
  params.form_factors.shadow_rays = 1;
  auto solver = make_radiosity_solver(s, mesh, params);
  stop_criterion stop;
  stop.remaining = 1e-6;
  run_solver(*solver, stop);
  const power_balance& balance = progressive_of(*solver)->balance;
  const double emitted = std::numbers::pi * 1.0 * 1.0;
  EXPECT_NEAR(balance.emitted.r, emitted, 1e-9);
  EXPECT_NEAR(balance.received.r / emitted, 0.5 * parallel_rectangles(1, 1, 1), 0.003);
  EXPECT_LT(balance_error(balance), 1e-9);
}

}  // namespace
}  // namespace bounce
