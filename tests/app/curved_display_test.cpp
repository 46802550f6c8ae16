// The live view's finer display of curved surfaces (curved_display.h):
// points on the true sphere, PN triangles for smooth polygon meshes, no
// cracks, blends of the solution, flat surfaces left alone.
#include <cmath>
#include <map>
#include <utility>

#include <gtest/gtest.h>

#include "mesh_builders.h"
#include "render/curved_display.h"

namespace bounce {
namespace {

using test_support::add_closed_box;
using test_support::add_material;
using test_support::mesh_of;

// Every undirected edge of a closed surface's triangles is used twice.
void expect_closed(const std::vector<unsigned int>& triangles, const std::string& what) {
  std::map<std::pair<unsigned, unsigned>, int> uses;
  for (std::size_t t = 0; t < triangles.size(); t += 3)
    for (int k = 0; k < 3; ++k) {
      const unsigned a = triangles[t + k], b = triangles[t + (k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  int open = 0;
  for (const auto& [edge, n] : uses) open += n != 2;
  EXPECT_EQ(open, 0) << what;
}

TEST(CurvedDisplay, SpherePointsLieOnTheSphereWithoutCracks) {
  scene s;
  const int m = add_material(s, rgb(0.5));
  surface ball;
  ball.name = "ball";
  ball.geometry = sphere{vec3(1, 2, 3), 2.0, m};
  s.surfaces.push_back(ball);
  const patch_mesh mesh = mesh_of(s, 1.5);  // coarse: a few dozen elements
  std::vector<unsigned> elements;
  for (const glm::ivec3& e : mesh.elements)
    elements.insert(elements.end(), {unsigned(e[0]), unsigned(e[1]), unsigned(e[2])});
  expect_closed(elements, "the solver's mesh");

  const gl::curved_display display = gl::make_curved_display(mesh, &s, 6.0);
  ASSERT_FALSE(display.positions.empty());  // the sphere is split
  expect_closed(display.triangles, "the display");
  EXPECT_GE(display.triangles.size() / 3, 16 * mesh.element_count());  // k >= 4 at this size
  for (std::size_t i = 0; i < display.positions.size(); ++i) {
    const vec3 out_of = display.positions[i] - vec3(1, 2, 3);
    ASSERT_NEAR(glm::length(out_of), 2.0, 1e-9) << i;
    ASSERT_NEAR(glm::dot(display.normals[i], glm::normalize(out_of)), 1.0, 1e-9) << i;
    const gl::vertex_blend& b = display.blends[i];
    EXPECT_NEAR(b.wa + b.wb + b.wc, 1.0f, 1e-6f);
    EXPECT_GE(std::min({b.wa, b.wb, b.wc}), 0.0f);
    EXPECT_LT(std::max({b.a, b.b, b.c}), mesh.vertex_count());
  }
  // Each element's triangles, and its outline: k segments a side.
  ASSERT_EQ(display.first.size(), mesh.element_count() + 1);
  EXPECT_EQ(display.first.back() * 3, display.triangles.size());
  const std::size_t k = std::size_t(std::lround(std::sqrt(double(display.first[1] - display.first[0]))));
  EXPECT_EQ(display.outline.size(), 2 * 3 * k * mesh.element_count());
}

TEST(CurvedDisplay, SmoothPolygonMeshesBulgeTowardsTheirSurface) {
  // A UV sphere of radius 1 given as polygons with its true normals: the
  // PN triangles put the display's points far closer to the sphere than
  // the flat elements' edge midpoints are.
  scene s;
  const int m = add_material(s, rgb(0.5));
  polygon_mesh poly;
  const int slices = 24, stacks = 12;
  for (int j = 0; j <= stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const double theta = 3.14159265358979 * j / stacks, phi = 2 * 3.14159265358979 * i / slices;
      const vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      poly.positions.push_back(p);
      poly.normals.push_back(p);
    }
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const int a = j * slices + i, b = j * slices + (i + 1) % slices, c = a + slices, d = b + slices;
      polygon_face f;
      f.position = {a, b, d, c};
      f.normal = f.position;
      f.material = m;
      poly.faces.push_back(f);
    }
  surface surf;
  surf.name = "uv_sphere";
  surf.geometry = poly;
  s.surfaces.push_back(surf);
  const patch_mesh mesh = mesh_of(s, 1.0);
  double flat_error = 0.0;
  for (const glm::ivec3& e : mesh.elements)
    for (int k = 0; k < 3; ++k)
      flat_error =
          std::max(flat_error, 1.0 - glm::length(0.5 * (mesh.positions[e[k]] + mesh.positions[e[(k + 1) % 3]])));
  const gl::curved_display display = gl::make_curved_display(mesh, &s);
  ASSERT_FALSE(display.positions.empty());
  double display_error = 0.0;
  for (const vec3& p : display.positions) display_error = std::max(display_error, std::abs(glm::length(p) - 1.0));
  std::printf("largest distance from the sphere: flat elements %.5f, display %.5f\n", flat_error, display_error);
  EXPECT_LT(display_error, 0.25 * flat_error);
}

TEST(CurvedDisplay, FlatSurfacesKeepTheirElements) {
  scene s;
  add_closed_box(s, vec3(0.0), vec3(1.0), add_material(s, rgb(0.5)));
  const patch_mesh mesh = mesh_of(s, 0.3);
  const gl::curved_display display = gl::make_curved_display(mesh, &s);
  EXPECT_TRUE(display.positions.empty());
  EXPECT_EQ(display.triangles.size(), 3 * mesh.element_count());
  EXPECT_EQ(display.outline.size(), 6 * mesh.element_count());
}

TEST(CurvedDisplay, TheTriangleBudgetHolds) {
  scene s;
  const int m = add_material(s, rgb(0.5));
  surface ball;
  ball.geometry = sphere{vec3(0.0), 1.0, m};
  s.surfaces.push_back(ball);
  const patch_mesh mesh = mesh_of(s, 0.8);
  const std::size_t budget = 4 * mesh.element_count();
  const gl::curved_display display = gl::make_curved_display(mesh, &s, 6.0, budget);
  EXPECT_LE(display.triangles.size() / 3, budget);
  EXPECT_GT(display.triangles.size() / 3, mesh.element_count());  // still split, less finely
  expect_closed(display.triangles, "the display within its budget");
}

}  // namespace
}  // namespace bounce
