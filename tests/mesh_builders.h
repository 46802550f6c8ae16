// Small scenes built in code for the radiosity tests.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "scene/scene.h"
#include "scene/scene_io.h"

namespace bounce::test_support {

// Adds a material and returns its index.
inline int add_material(scene& s, rgb rho, rgb ke = rgb(0.0)) {
  material m;
  m.name = "m" + std::to_string(s.materials.size());
  m.rho = rho;
  m.ke = ke;
  s.materials.push_back(m);
  return int(s.materials.size()) - 1;
}

// Adds one planar polygon as its own surface (counter-clockwise seen from
// the side it faces).
inline void add_polygon(scene& s, std::vector<vec3> corners, int material, const std::string& name = "") {
  polygon_mesh mesh;
  polygon_face face;
  for (std::size_t i = 0; i < corners.size(); ++i) face.position.push_back(int(i));
  face.material = material;
  mesh.positions = std::move(corners);
  mesh.faces.push_back(face);
  surface surf;
  surf.name = name.empty() ? "polygon" + std::to_string(s.surfaces.size()) : name;
  surf.geometry = std::move(mesh);
  s.surfaces.push_back(std::move(surf));
}

// An axis-aligned box [lo, hi] seen from inside: six faces facing in.
inline void add_closed_box(scene& s, vec3 lo, vec3 hi, int material) {
  const vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                     {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  const int faces[6][4] = {{0, 1, 2, 3}, {5, 4, 7, 6}, {4, 0, 3, 7}, {1, 5, 6, 2}, {4, 5, 1, 0}, {3, 2, 6, 7}};
  for (const auto& f : faces) add_polygon(s, {c[f[0]], c[f[1]], c[f[2]], c[f[3]]}, material);
}

// The white furnace: the inside of the box [-1, 1]^3, every face emitting
// Ke = 1 and reflecting rho, so B = pi / (1 - rho) everywhere.
inline scene furnace(double rho) {
  scene s;
  const int m = add_material(s, rgb(rho), rgb(1.0));
  add_closed_box(s, vec3(-1.0), vec3(1.0), m);
  return s;
}

// The scene's patch mesh at `max_edge` (crease angle 30 degrees, elements
// as patches).
inline patch_mesh mesh_of(const scene& s, double max_edge) {
  patch_mesh mesh;
  std::string error;
  EXPECT_TRUE(make_patch_mesh(s, {max_edge, 30.0}, mesh, error)) << error;
  return mesh;
}

// The same with shooting patches of `patch_edge` and, when above 0,
// adaptive meshing's a priori pass down to `a_priori_min_edge`.
inline patch_mesh mesh_of(const scene& s, double max_edge, double patch_edge, double a_priori_min_edge = 0.0) {
  mesher_params params;
  params.max_edge = max_edge;
  params.patch_edge = patch_edge;
  params.a_priori_min_edge = a_priori_min_edge;
  patch_mesh mesh;
  std::string error;
  EXPECT_TRUE(make_patch_mesh(s, params, mesh, error)) << error;
  return mesh;
}

// A scene that must load (the test fails, naming the error, if not).
// A JSON scene around one surface entry, with a light so it is valid.
inline std::string json_scene(const std::string& surface_json, const std::string& extra = "") {
  return R"({
  "materials": {"white": {"rho": [0.5, 0.5, 0.5]}},
  "surfaces": [)" +
         surface_json + R"(],
  "lights": [{"position": [0, 5, 0], "intensity": [1, 1, 1]}])" +
         extra + "\n}\n";
}

inline scene load_ok(const std::string& path) {
  scene s;
  load_report report;
  EXPECT_TRUE(load_scene(path, s, report)) << report.error;
  return s;
}

// Loads a scene that must fail and returns the message.
inline std::string load_error_of(const std::string& path) {
  scene s;
  load_report report;
  EXPECT_FALSE(load_scene(path, s, report)) << "loading " << path << " should fail";
  EXPECT_FALSE(report.error.empty());
  return report.error;
}

// The embedded Cornell box, as every command loads it without a scene.
inline scene default_cornell_box() {
  return load_ok(default_scene_path);
}

}  // namespace bounce::test_support
