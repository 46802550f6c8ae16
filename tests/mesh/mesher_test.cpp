// The patch mesher: element sizes, conformity, areas, where vertices are
// shared and where they are split, receive points.
#include <cmath>
#include <map>
#include <numbers>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh_builders.h"
#include "scene/scene_io.h"
#include "test_files.h"

namespace bounce {
namespace {

using test_support::add_material;
using test_support::add_polygon;

scene cornell() {
  scene s;
  load_report report;
  EXPECT_TRUE(load_scene(default_scene_path, s, report)) << report.error;
  return s;
}

using test_support::mesh_of;

double polygon_area(const polygon_mesh& m, const polygon_face& f) {
  vec3 newell(0.0);
  for (std::size_t i = 0; i < f.position.size(); ++i)
    newell += glm::cross(m.positions[f.position[i]], m.positions[f.position[(i + 1) % f.position.size()]]);
  return 0.5 * glm::length(newell);
}

TEST(Mesher, ElementsAreNoLongerThanMaxEdge) {
  for (double max_edge : {200.0, 60.0}) {
    patch_mesh mesh = mesh_of(cornell(), max_edge);
    for (const glm::ivec3& t : mesh.elements)
      for (int k = 0; k < 3; ++k)
        EXPECT_LE(glm::length(mesh.positions[t[k]] - mesh.positions[t[(k + 1) % 3]]), max_edge * (1 + 1e-12));
  }
}

TEST(Mesher, AreaIsPreservedPerSurface) {
  scene s = cornell();
  patch_mesh mesh = mesh_of(s, 50.0);
  std::vector<double> area(s.surfaces.size(), 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) area[mesh.element_surfaces[e]] += mesh.element_areas[e];
  double total = 0.0, total_expected = 0.0;
  for (std::size_t i = 0; i < s.surfaces.size(); ++i) {
    const auto& poly = std::get<polygon_mesh>(s.surfaces[i].geometry);
    double expected = 0.0;
    for (const polygon_face& f : poly.faces) expected += polygon_area(poly, f);
    total += area[i];
    total_expected += expected;
    // The floor loses the ground under the blocks (coplanar_cut.h, contacts).
    if (s.surfaces[i].name != "floor") {
      EXPECT_NEAR(area[i] / expected, 1.0, 1e-12) << s.surfaces[i].name;
    }
  }
  EXPECT_GT(mesh.contact_area_removed, 0.0);
  EXPECT_NEAR(total / (total_expected - mesh.contact_area_removed), 1.0, 1e-12);
}

// No vertex of a surface lies inside an edge of another element of the same
// surface: the mesh has no T-vertices, so Gouraud shading has no cracks.
TEST(Mesher, ConformingInsideEachSurface) {
  patch_mesh mesh = mesh_of(cornell(), 90.0);
  std::size_t checked = 0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.elements[e][k], b = mesh.elements[e][(k + 1) % 3];
      const vec3 pa = mesh.positions[a], pb = mesh.positions[b];
      const double length = glm::length(pb - pa);
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        if (int(v) == a || int(v) == b || mesh.vertex_surfaces[v] != mesh.element_surfaces[e]) continue;
        const vec3 d = mesh.positions[v] - pa;
        const double along = glm::dot(d, pb - pa) / (length * length);
        const double off = glm::length(d - along * (pb - pa));
        const bool inside = along > 1e-9 && along < 1 - 1e-9 && off < 1e-9 * length;
        EXPECT_FALSE(inside) << "vertex " << v << " lies inside an edge of element " << e;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 1000u);
}

TEST(Mesher, VerticesAreSplitAtCornersAndSharedOnFlatSurfaces) {
  scene s = cornell();
  patch_mesh mesh = mesh_of(s, 100.0);
  std::map<std::tuple<double, double, double>, std::vector<int>> at;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    at[{mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z}].push_back(int(v));
  // The floor's corner under the back wall and the green wall: one vertex
  // per surface (floor, back wall, green wall), each with its own normal.
  const auto& corner = at[{0.0, 0.0, 559.2}];
  ASSERT_EQ(corner.size(), 3u);
  for (int v : corner)
    for (int u : corner)
      if (u != v) {
        EXPECT_LT(glm::dot(mesh.normals[u], mesh.normals[v]), 0.5);
      }
  // Inside one surface two vertices share a position only across a crease
  // (a block's edges): the ceiling's eight pieces are welded into one mesh.
  for (const auto& [position, vertices] : at)
    for (std::size_t i = 0; i < vertices.size(); ++i)
      for (std::size_t j = i + 1; j < vertices.size(); ++j)
        if (mesh.vertex_surfaces[vertices[i]] == mesh.vertex_surfaces[vertices[j]]) {
          EXPECT_LT(glm::dot(mesh.normals[vertices[i]], mesh.normals[vertices[j]]), std::cos(glm::radians(30.0)))
              << "duplicate vertex in surface " << s.surfaces[mesh.vertex_surfaces[vertices[i]]].name;
        }
  // The ceiling (a flat surface of eight pieces) has no duplicates at all.
  std::size_t ceiling_vertices = 0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    if (s.surfaces[mesh.vertex_surfaces[v]].name == "ceiling") ++ceiling_vertices;
  std::size_t ceiling_positions = 0;
  for (const auto& [position, vertices] : at)
    for (int v : vertices)
      if (s.surfaces[mesh.vertex_surfaces[v]].name == "ceiling") {
        ++ceiling_positions;
        break;
      }
  EXPECT_EQ(ceiling_vertices, ceiling_positions);
}

// A ball of radius 0.5 at (1, 2, 3), material 0 grey.
scene ball_at_123() {
  scene s;
  const int white = add_material(s, rgb(0.5));
  surface ball;
  ball.name = "ball";
  ball.geometry = sphere{vec3(1, 2, 3), 0.5, white};
  s.surfaces.push_back(ball);
  return s;
}

TEST(Mesher, CurvedSurfacesKeepTheirTrueNormalsAndShareVertices) {
  scene s = ball_at_123();
  patch_mesh mesh = mesh_of(s, 0.1);
  ASSERT_GT(mesh.element_count(), 200u);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const vec3 radial = (mesh.positions[v] - vec3(1, 2, 3)) / 0.5;
    EXPECT_NEAR(glm::length(radial), 1.0, 1e-12);
    EXPECT_NEAR(glm::dot(mesh.normals[v], radial), 1.0, 1e-9);
    EXPECT_EQ(mesh.receive_points[v], mesh.positions[v]);  // closed: no boundary
  }
  // Closed and conforming: every edge is shared by exactly two elements.
  std::map<std::pair<int, int>, int> edges;
  for (const glm::ivec3& t : mesh.elements)
    for (int k = 0; k < 3; ++k) ++edges[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
  for (const auto& [edge, count] : edges) EXPECT_EQ(count, 2);
}

// A split of a curved surface's element follows the curve through its
// ends' tangent planes, not the flat facet: on a sphere at the curvature
// bound (20 degrees an edge, 28 across a cell) the new vertices lie within
// 0.2% of the radius (measured: 0.14% at worst), where chord midpoints fall
// 1.5-3% inside; a flat surface's stay in its plane.
TEST(Mesher, SplitsOfCurvedSurfacesFollowTheCurve) {
  scene s = ball_at_123();
  add_polygon(s, {{-2, -1, -2}, {-2, -1, 2}, {2, -1, 2}, {2, -1, -2}}, 0);
  patch_mesh mesh = mesh_of(s, 10.0);
  ASSERT_EQ(mesh.curved_surfaces, (std::vector<bool>{true, false}));
  const std::size_t old_vertices = mesh.vertex_count();
  std::vector<int> every(mesh.element_count());
  for (std::size_t e = 0; e < every.size(); ++e) every[e] = int(e);
  std::vector<int> origin;
  std::string error;
  ASSERT_TRUE(refine_patch_mesh(mesh, every, 0.0, origin, error)) << error;
  std::size_t on_ball = 0;
  for (std::size_t v = old_vertices; v < mesh.vertex_count(); ++v) {
    if (mesh.vertex_surfaces[v] == 0) {
      ++on_ball;
      EXPECT_NEAR(glm::distance(mesh.positions[v], vec3(1, 2, 3)), 0.5, 0.002 * 0.5);
    } else {
      EXPECT_NEAR(mesh.positions[v].y, -1.0, 1e-12);
    }
  }
  EXPECT_GT(on_ball, 100u);
}

TEST(Mesher, ElementsKnowTheirSurfaceMaterialAndPoints) {
  scene s = cornell();
  patch_mesh mesh = mesh_of(s, 100.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const glm::ivec3 t = mesh.elements[e];
    const std::string& name = s.surfaces[mesh.element_surfaces[e]].name;
    const std::string& material = s.materials[mesh.element_materials[e]].name;
    if (name == "light") {
      EXPECT_EQ(material, "light");
    }
    if (name == "left_wall") {
      EXPECT_EQ(material, "red");
    }
    for (int k = 0; k < 3; ++k) EXPECT_EQ(mesh.vertex_surfaces[t[k]], mesh.element_surfaces[e]);
    // Barycentric coordinates map points back to the element's vertices.
    const vec3 centroid = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
    const vec3 w = barycentric(mesh, int(e), centroid);
    EXPECT_NEAR(w.x, 1.0 / 3, 1e-9);
    EXPECT_NEAR(w.y, 1.0 / 3, 1e-9);
    const vec3 corner = barycentric(mesh, int(e), mesh.positions[t[1]]);
    EXPECT_NEAR(corner.y, 1.0, 1e-9);
    // Geometric normal agrees with the vertices' side.
    EXPECT_GT(glm::dot(mesh.element_normals[e], mesh.normals[t[0]]), 0.99);
  }
  // The light emits pi * Ke.
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    if (s.surfaces[mesh.vertex_surfaces[v]].name == "light") {
      EXPECT_NEAR(mesh.vertex_emission[v].r, std::numbers::pi * 17, 1e-12);
    }
}

TEST(Mesher, BoundaryVerticesReceiveJustInsideTheirFaces) {
  scene s;
  int white = add_material(s, rgb(0.5));
  add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, white);
  patch_mesh mesh = mesh_of(s, 0.25);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const vec3 p = mesh.positions[v], r = mesh.receive_points[v];
    const bool boundary = p.x == 0 || p.x == 1 || p.y == 0 || p.y == 1;
    if (!boundary) {
      EXPECT_EQ(r, p);
      continue;
    }
    const double distance = glm::length(r - p);
    EXPECT_GT(distance, 0.0);
    EXPECT_LT(distance, 1e-3);
    EXPECT_EQ(r.z, 0.0);  // in the surface's plane
    EXPECT_TRUE(r.x > 0 && r.x < 1 && r.y > 0 && r.y < 1) << "receive point outside its face";
  }
}

TEST(Mesher, TexturesScaleReflectanceByTheirMean) {
  scene s;
  texture checks;
  checks.kind = texture_kind::checker;
  checks.color0 = rgb(1.0);
  checks.color1 = rgb(0.2, 0.4, 0.6);
  s.textures.push_back(checks);
  int m = add_material(s, rgb(0.5));
  s.materials[m].texture = 0;
  add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, m);
  patch_mesh mesh = mesh_of(s, 1.0);
  EXPECT_NEAR(mesh.vertex_rho[0].r, 0.5 * 0.6, 1e-12);
  EXPECT_NEAR(mesh.vertex_rho[0].b, 0.5 * 0.8, 1e-12);
}

// Two unit squares side by side in one surface, whose uvs jump across the
// shared edge (u = x on the left, x + 4 on the right): a texture seam.
TEST(Mesher, VerticesCarryUvsAndTexturedOnesSplitAtSeams) {
  std::size_t on_seam[2] = {0, 0};  // vertices on the shared edge: untextured, textured
  for (const bool textured : {true, false}) {
    scene s;
    s.textures.push_back(texture{});
    const int m = add_material(s, rgb(0.5));
    if (textured) s.materials[m].texture = 0;
    polygon_mesh pm;
    pm.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
    pm.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {5, 0}, {6, 0}, {6, 1}, {5, 1}};
    pm.faces.push_back({{0, 1, 2, 3}, {}, {0, 1, 2, 3}, m, 0});
    pm.faces.push_back({{1, 4, 5, 2}, {}, {4, 5, 6, 7}, m, 0});
    s.surfaces.push_back({"two squares", "", pm});
    patch_mesh mesh = mesh_of(s, 0.3);
    ASSERT_EQ(mesh.uvs.size(), mesh.vertex_count());
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
      if (mesh.positions[v].x == 1.0) ++on_seam[textured];
    if (!textured) continue;  // welded across the seam: one uv per vertex cannot hold both
    // Every corner's uv is its own square's map of its position, after
    // meshing and after a round of refinement (new vertices interpolate).
    auto expect_uvs = [](const patch_mesh& mesh) {
      for (std::size_t e = 0; e < mesh.element_count(); ++e) {
        const glm::ivec3 t = mesh.elements[e];
        const double centre = (mesh.positions[t[0]].x + mesh.positions[t[1]].x + mesh.positions[t[2]].x) / 3.0;
        for (int k = 0; k < 3; ++k) {
          const vec3 p = mesh.positions[t[k]];
          const vec2 expected(centre < 1.0 ? p.x : p.x + 4.0, p.y);
          ASSERT_NEAR(mesh.uvs[t[k]].x, expected.x, 1e-12) << "element " << e;
          ASSERT_NEAR(mesh.uvs[t[k]].y, expected.y, 1e-12) << "element " << e;
        }
      }
    };
    expect_uvs(mesh);
    std::vector<int> all(mesh.element_count());
    for (std::size_t e = 0; e < all.size(); ++e) all[e] = int(e);
    std::vector<int> origin;
    std::string error;
    const std::size_t before = mesh.vertex_count();
    ASSERT_TRUE(refine_patch_mesh(mesh, all, 0.01, origin, error)) << error;
    ASSERT_GT(mesh.vertex_count(), before);
    ASSERT_EQ(mesh.uvs.size(), mesh.vertex_count());
    expect_uvs(mesh);
  }
  // Each side keeps its own vertices along the seam only when textured.
  EXPECT_GT(on_seam[0], 0u);
  EXPECT_EQ(on_seam[1], 2 * on_seam[0]);
}

TEST(Mesher, PatchesAreTiledExactlyByTheirElements) {
  scene s = cornell();
  patch_mesh mesh;
  std::string error;
  ASSERT_TRUE(make_patch_mesh(s, {50.0, 30.0, 200.0}, mesh, error)) << error;
  ASSERT_LT(mesh.patch_count(), mesh.element_count() / 4);
  std::vector<double> covered(mesh.patch_count(), 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const int p = mesh.element_patches[e];
    covered[p] += mesh.element_areas[e];
    // The element's centroid lies inside its patch's triangle, in its plane.
    const glm::ivec3 t = mesh.elements[e];
    const vec3 c = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
    const auto& k = mesh.patch_corners[p];
    EXPECT_NEAR(glm::dot(c - k[0], mesh.patch_normals[p]), 0.0, 1e-9);
    for (int i = 0; i < 3; ++i)
      EXPECT_GE(glm::dot(glm::cross(k[(i + 1) % 3] - k[i], c - k[i]), mesh.patch_normals[p]), 0.0);
  }
  for (std::size_t p = 0; p < mesh.patch_count(); ++p) EXPECT_NEAR(covered[p] / mesh.patch_areas[p], 1.0, 1e-12);
  // Without a patch size, every element is its own patch.
  patch_mesh plain = mesh_of(s, 50.0);
  EXPECT_EQ(plain.patch_count(), plain.element_count());
  for (std::size_t e = 0; e < plain.element_count(); ++e) EXPECT_EQ(plain.element_patches[e], int(e));
}

TEST(Mesher, RefusesAbsurdSizes) {
  patch_mesh mesh;
  std::string error;
  EXPECT_FALSE(make_patch_mesh(cornell(), {0.01, 30.0}, mesh, error));
  EXPECT_NE(error.find("use a larger --max-edge"), std::string::npos) << error;
}

}  // namespace
}  // namespace bounce
