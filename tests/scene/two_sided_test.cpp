// Two-sided materials: both sides of a surface receive, reflect and emit
// with their own radiosity, in the solvers and in the tracers.
#include <cmath>
#include <numbers>
#include <tuple>

#include <gtest/gtest.h>

#include "mesh/patch_mesh.h"
#include "mesh_builders.h"
#include "radiosity/solver.h"
#include "scene/camera_math.h"
#include "scene/scene_io.h"
#include "scene/two_sided.h"
#include "test_files.h"
#include "trace/back_faces.h"
#include "trace/radiosity_field.h"
#include "trace/ray_tracer.h"

namespace bounce {
namespace {

using std::numbers::pi;
using test_support::add_material;
using test_support::add_polygon;
using test_support::mesh_of;

TEST(TwoSided, BacksAreTheSameFacesTurnedOver) {
  scene s;
  const int one = add_material(s, rgb(0.5));
  const int two = add_material(s, rgb(0.5));
  s.materials[std::size_t(two)].two_sided = true;
  add_polygon(s, {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}}, two);
  add_polygon(s, {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}}, one);
  s.surfaces.push_back({"ball", "", sphere{vec3(5.0), 1.0, two}});
  quadric q;
  q.a = q.b = q.c = 1.0;
  q.k = -1.0;
  q.material = two;
  s.surfaces.push_back({"quadric", "", q});
  const std::vector<std::string> warnings = add_back_sides(s);
  ASSERT_EQ(s.surfaces.size(), 6u);  // the triangle and the quadric got backs; the sphere cannot
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("ball: two_sided has no effect on a sphere"), std::string::npos);
  const surface& back = s.surfaces[4];
  EXPECT_EQ(back.back_of, 0);
  EXPECT_EQ(s.surfaces[0].back_side, 4);
  EXPECT_EQ(s.surfaces[1].back_side, -1);
  const polygon_mesh& m = std::get<polygon_mesh>(back.geometry);
  EXPECT_EQ(m.faces[0].position, (std::vector<int>{2, 1, 0}));
  EXPECT_EQ(std::get<quadric>(s.surfaces[5].geometry).k, 1.0);
  EXPECT_TRUE(add_back_sides(s).size() == 1 && s.surfaces.size() == 6u);  // no second backs
}

// A two-sided plane under a uniform sky of radiance L: the sky below the
// horizon has radiance L too, so both sides get B = rho pi L.
TEST(TwoSided, BothSidesReceiveTheirOwnLight) {
  scene s;
  const int m = add_material(s, rgb(0.5));
  s.materials[std::size_t(m)].two_sided = true;
  add_polygon(s, {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}, m);
  s.sky.zenith = rgb(2.0);
  s.sky.horizon = rgb(1.0);  // the lower side sees only the horizon's radiance: B = rho pi Lh
  add_back_sides(s);
  const patch_mesh mesh = mesh_of(s, 0.5);
  for (const solver_method method : {solver_method::progressive, solver_method::hierarchical}) {
    radiosity_params p;
    p.method = method;
    auto solver = make_radiosity_solver(s, mesh, p);
    stop_criterion stop;
    stop.remaining = 1e-9;
    stop.max_steps = 400;
    run_solver(*solver, stop);
    const auto solution = make_snapshot(*solver);
    int up = 0, down = 0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      if (mesh.normals[v].y > 0.5) {
        ++up;
        EXPECT_NEAR(solution->radiosity[v].r, 0.5 * (pi * 1.0 + 2.0 * pi / 3.0), 0.02 * 0.5 * 3.0 * pi) << v;
      } else {
        ++down;
        EXPECT_NEAR(solution->radiosity[v].r, 0.5 * pi * 1.0, 1e-9) << name_of(method) << " vertex " << v;
      }
    }
    EXPECT_GT(up, 4);
    EXPECT_EQ(up, down);
  }
}

// A floor modelled upside down under a lamp: black when one-sided, lit
// like the right way up when two-sided, in the two-pass still and the path
// tracer alike.
TEST(TwoSided, AnUpsideDownFloorIsLitWhenTwoSided) {
  auto room = [](bool upside_down, bool two_sided) {
    scene s;
    const int floor = add_material(s, rgb(0.6));
    s.materials[std::size_t(floor)].two_sided = two_sided;
    const int lamp = add_material(s, rgb(0.0), rgb(5.0));
    std::vector<vec3> corners = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    if (upside_down) std::reverse(corners.begin(), corners.end());
    add_polygon(s, corners, floor);
    add_polygon(s, {{-0.3, 1, -0.3}, {0.3, 1, -0.3}, {0.3, 1, 0.3}, {-0.3, 1, 0.3}}, lamp);  // faces down
    add_back_sides(s);
    s.view.eye = {0, 0.9, 1.2};
    s.view.target = {0, 0, 0};
    s.view.width = s.view.height = 24;
    return s;
  };
  auto mean_floor = [](const scene& s, integrator method) {
    const patch_mesh mesh = mesh_of(s, 0.2);
    auto solver = make_radiosity_solver(s, mesh, radiosity_params{});
    stop_criterion stop;
    stop.remaining = 1e-6;
    run_solver(*solver, stop);
    const auto solution = make_snapshot(*solver);
    const radiosity_field field(solved_mesh(*solver), solution->radiosity, solution->direct);
    const ray_scene rays(s);
    trace_params p;
    p.method = method;
    p.spp = method == integrator::path ? 64 : 4;
    const image img = trace_image(s, s.view, rays, &field, p);
    double sum = 0.0;
    for (float v : img.pixels) sum += v;
    return sum / double(img.pixels.size());
  };
  for (const integrator method : {integrator::whitted, integrator::path}) {
    const double right = mean_floor(room(false, false), method);
    const double black = mean_floor(room(true, false), method);
    const double fixed = mean_floor(room(true, true), method);
    EXPECT_LT(black, 0.05 * right) << int(method);
    EXPECT_NEAR(fixed, right, 0.03 * right) << int(method);
  }
}

TEST(TwoSided, SceneFilesAndGltfSayIt) {
  test_support::scratch_dir dir;
  scene s;
  load_report report;
  ASSERT_TRUE(load_scene(dir.write("t.json", R"({"materials": {"paper": {"rho": [0.5, 0.5, 0.5], "two_sided": true},
      "lamp": {"ke": [1, 1, 1]}},
    "surfaces": [{"polygon": [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]], "material": "paper"},
                 {"polygon": [[0, 1, 0], [1, 1, 0], [1, 1, 1]], "material": "lamp"}]})"),
                         s, report))
      << report.error;
  ASSERT_EQ(s.surfaces.size(), 3u);
  EXPECT_EQ(s.surfaces[2].back_of, 0);
  load_report bad;
  EXPECT_FALSE(load_scene(dir.write("b.json", R"({"materials": {"paper": {"two_sided": 1}},
    "surfaces": [{"polygon": [[0, 0, 0], [1, 0, 0], [1, 0, 1]], "material": "paper"}]})"),
                          s, bad));
  EXPECT_NE(bad.error.find("materials.paper.two_sided"), std::string::npos) << bad.error;
}

// The view of an upside-down floor is mostly back faces, and warned about;
// the same floor two-sided, or the right way up, is not.
TEST(TwoSided, AViewOfMostlyBackFacesIsWarnedAbout) {
  for (const auto& [upside_down, two_sided, expected] :
       std::vector<std::tuple<bool, bool, double>>{{false, false, 0.0}, {true, false, 1.0}, {true, true, 0.0}}) {
    scene s;
    const int floor = add_material(s, rgb(0.5));
    s.materials[std::size_t(floor)].two_sided = two_sided;
    std::vector<vec3> corners = {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}};
    if (upside_down) std::reverse(corners.begin(), corners.end());
    add_polygon(s, corners, floor);
    add_back_sides(s);
    s.view.eye = {0, 2, 0.5};
    s.view.target = {0, 0, 0};
    const double fraction = back_face_fraction(s, s.view, ray_scene(s));
    EXPECT_DOUBLE_EQ(fraction, expected) << upside_down << two_sided;
    EXPECT_EQ(back_face_warning(fraction).empty(), expected < 0.5);
  }
  EXPECT_NE(back_face_warning(0.62).find("(62% of what it hits)"), std::string::npos);
}

}  // namespace
}  // namespace bounce
