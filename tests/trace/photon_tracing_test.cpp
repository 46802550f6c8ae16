// The caustic light pass against closed forms: a glass slab, a mirror, the
// power balance, determinism.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "mesh_builders.h"
#include "scene/scene_io.h"
#include "test_files.h"
#include "optics/optics.h"
#include "trace/photon_tracing.h"

namespace bounce {
namespace {

using std::numbers::pi;
using test_support::add_closed_box;
using test_support::add_material;
using test_support::add_polygon;

// Square of half-width `a` in the plane y = `height`, facing up or down.
void add_square(scene& s, double a, double height, bool facing_up, int material) {
  if (facing_up)
    add_polygon(s, {{-a, height, -a}, {-a, height, a}, {a, height, a}, {a, height, -a}}, material);
  else
    add_polygon(s, {{-a, height, -a}, {a, height, -a}, {a, height, a}, {-a, height, a}}, material);
}

int add_glass(scene& s, rgb kt = rgb(1.0)) {
  const int m = add_material(s, rgb(0.0));
  s.materials[m].kt = kt;
  s.materials[m].ior = 1.5;
  s.materials[m].fresnel = true;
  return m;
}

// A closed box facing out (add_closed_box's faces look in).
void add_solid_box(scene& s, vec3 lo, vec3 hi, int material) {
  const std::size_t first = s.surfaces.size();
  add_closed_box(s, lo, hi, material);
  for (std::size_t i = first; i < s.surfaces.size(); ++i)
    for (polygon_face& f : std::get<polygon_mesh>(s.surfaces[i].geometry).faces)
      std::reverse(f.position.begin(), f.position.end());
}

// Four binomial standard deviations of the fraction of n photons that
// land, when each lands with probability about p.
double four_sigma(double p, double n) {
  return 4.0 * std::sqrt(p * (1.0 - p) / n);
}

TEST(CausticPhotons, GlassSlabPassesFresnelTransmissionSummedOverInnerReflections) {
  // A small emitter (0.1 x 0.1, ke 10) at y = 4 facing down on a glass slab
  // (y in [1, 2], 400 wide: it takes every photon but 1e-4 of them, at
  // grazing angles) over a diffuse floor at y = 0.
  scene s;
  const int light = add_material(s, rgb(0.0), rgb(10.0));
  const int floor = add_material(s, rgb(0.5));
  const int glass = add_glass(s);
  add_square(s, 0.05, 4.0, false, light);
  add_square(s, 400.0, 0.0, true, floor);
  add_solid_box(s, vec3(-200, 1, -200), vec3(200, 2, 200), glass);
  const ray_scene rays(s);
  photon_params params;
  params.photon_count = 200000;
  const caustic_result result = caustic_photons(s, rays, params);
  const photon_stats& st = result.stats;

  // A photon arriving at angle theta enters with 1 - F, and leaves through
  // the bottom after m round trips inside with (1 - F) F^2m (the inner
  // angle has the same F). The floor is reached after 2 + 2m specular
  // events: m <= 7 within the 16 allowed. Cosine-weighted emission makes
  // u = sin^2 theta uniform.
  const double emitted = pi * 10.0 * 0.01;
  EXPECT_NEAR(st.emitted_power.r, emitted, 1e-9 * emitted);
  double expected = 0.0, no_inner = 0.0;
  const int steps = 100000;
  for (int i = 0; i < steps; ++i) {
    const double u = (i + 0.5) / steps, f = fresnel_dielectric(std::sqrt(1.0 - u), 1.0, 1.5);
    double inner = 0.0;
    for (int m = 0; m <= 7; ++m) inner += std::pow(f, 2 * m);
    expected += (1 - f) * (1 - f) * inner / steps;
    no_inner += (1 - f) * (1 - f) / steps;
  }
  const double tolerance = four_sigma(expected, double(st.emitted));
  ASSERT_GT(expected - no_inner, 2.0 * tolerance);  // the test tells whether inner reflections are followed
  EXPECT_NEAR(caustic_power_fraction(st), expected, tolerance);
  // Every photon stored lies on the floor, arrived from above, and carries
  // the emitted photon's power (grey glass: roulette keeps it).
  ASSERT_GT(result.map.size(), 0u);
  for (const photon& p : result.map.photons()) {
    ASSERT_EQ(p.surface, 1);
    ASSERT_NEAR(p.position.y, 0.0, 1e-9);
    ASSERT_GT(p.incoming.y, 0.0);
    ASSERT_NEAR(p.power.g, emitted / double(st.emitted), 1e-12);
  }
  EXPECT_EQ(st.reweighted_power, rgb(0.0));

  // Straight below the emitter the floor sees it through the slab, which
  // brings it closer by t (1 - 1 / n) = 1/3 (paraxial): E = T(0) L A / d^2.
  // 200 000 photons put about 1100 within 0.3: 4 sigma is 12 %; the disc
  // averages the cos^4 fall-off within 1 %.
  const double f0 = std::pow(0.5 / 2.5, 2), t0 = (1 - f0) / (1 + f0);
  const double below = t0 * 10.0 * 0.01 / std::pow(4.0 - 1.0 / 3.0, 2);
  const photon_estimate e = result.map.estimate(vec3(0.0), vec3(0, 1, 0), 0.3, 100000, photon_filter::box);
  EXPECT_GT(e.photons, 800);
  EXPECT_NEAR(e.irradiance.r, below, (4.0 / std::sqrt(double(e.photons)) + 0.01) * below);
}

TEST(CausticPhotons, MirrorSendsKrOfWhatReachesItToAFloorTheEmitterCannotSee) {
  // An emitter (0.01 x 0.01) at y = 1 facing up, a mirror (kr 0.7) of
  // half-width 1 at y = 2 facing down, a diffuse floor at y = 0 that sees
  // only the emitter's back.
  scene s;
  const int light = add_material(s, rgb(0.0), rgb(100.0));
  const int floor = add_material(s, rgb(0.5));
  const int mirror = add_material(s, rgb(0.0));
  s.materials[mirror].kr = rgb(0.7);
  add_square(s, 0.005, 1.0, true, light);
  add_square(s, 50.0, 0.0, true, floor);
  add_square(s, 1.0, 2.0, false, mirror);
  const ray_scene rays(s);
  const caustic_result result = caustic_photons(s, rays, photon_params{});
  const photon_stats& st = result.stats;

  // Form factor from a point to a parallel square of half-width a centred
  // above it at height c: four times the corner case (Howell's catalogue,
  // B-3). The photons leave from the emitter lifted by the surface offset.
  const double a = 1.0, c = 1.0 - rays.surface_offset(), x = a / c;
  const double corner =
      (x / std::sqrt(1 + x * x) * std::atan(x / std::sqrt(1 + x * x))) / pi;  // both terms alike for a square
  const double to_mirror = 4.0 * corner;
  const double n = double(st.emitted), emitted = st.emitted_power.r;
  EXPECT_NEAR(emitted, pi * 100.0 * 1e-4, 1e-12);
  EXPECT_NEAR(st.stored_power.r / emitted, 0.7 * to_mirror, four_sigma(0.7 * to_mirror, n));
  EXPECT_NEAR(st.absorbed_power.r / emitted, 0.3 * to_mirror, four_sigma(0.3 * to_mirror, n));
  EXPECT_NEAR(st.escaped_power.r / emitted, 1.0 - to_mirror, four_sigma(to_mirror, n));
  EXPECT_EQ(st.direct_power, rgb(0.0));
  // The mirror's image of the emitter lights the floor within
  // a (2 c + 1) / c of the middle.
  for (const photon& p : result.map.photons()) {
    ASSERT_EQ(p.surface, 1);
    ASSERT_LT(std::max(std::abs(p.position.x), std::abs(p.position.z)), 3.0 + 0.01);
  }
}

// A closed room (diffuse walls, an emitting square in the ceiling, a point
// light) with a tinted glass ball and a ball that is partly mirror and
// partly diffuse.
scene caustic_room() {
  scene s;
  const int wall = add_material(s, rgb(0.6, 0.5, 0.4));
  const int light = add_material(s, rgb(0.0), rgb(8.0, 6.0, 4.0));
  const int glass = add_glass(s, rgb(0.9, 0.8, 0.6));
  const int shiny = add_material(s, rgb(0.2));
  s.materials[shiny].kr = rgb(0.6, 0.7, 0.5);
  add_closed_box(s, vec3(-2, 0, -2), vec3(2, 4, 2), wall);
  add_square(s, 0.4, 3.999, false, light);
  s.lights.push_back({vec3(1.0, 3.0, -1.0), rgb(5.0, 5.0, 3.0)});
  surface ball;
  ball.geometry = sphere{vec3(-0.5, 0.8, 0.3), 0.8, glass};
  s.surfaces.push_back(ball);
  ball.geometry = sphere{vec3(1.0, 0.6, 0.5), 0.6, shiny};
  s.surfaces.push_back(ball);
  return s;
}

bool same_photons(const photon_map& a, const photon_map& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const photon &p = a.photons()[i], &q = b.photons()[i];
    if (p.position != q.position || p.incoming != q.incoming || p.power != q.power || p.normal != q.normal ||
        p.surface != q.surface)
      return false;
  }
  return true;
}

TEST(CausticPhotons, EveryWattEmittedIsAccountedFor) {
  const scene s = caustic_room();
  const ray_scene rays(s);
  photon_params params;
  params.photon_count = 50000;
  const caustic_result result = caustic_photons(s, rays, params);
  const photon_stats& st = result.stats;
  // The emitters' power, exactly: pi ke A for the square, 4 pi I for the
  // point light.
  const rgb power = pi * rgb(8.0, 6.0, 4.0) * 0.64 + 4.0 * pi * rgb(5.0, 5.0, 3.0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(st.emitted_power[c], power[c], 1e-9 * power[c]);
    EXPECT_NEAR(photon_power_imbalance(st)[c], 0.0, 1e-9 * power[c]) << c;
    EXPECT_NEAR(st.stored_power[c], result.map.total_power()[c], 1e-9 * power[c]);
  }
  EXPECT_EQ(st.stored, result.map.size());
  EXPECT_EQ(st.escaped_power, rgb(0.0));  // closed room
  // Each term of the balance is there: the tinted glass reweights, the
  // partly diffuse ball stores and passes photons on, the walls take the
  // direct light.
  EXPECT_NE(st.reweighted_power, rgb(0.0));
  EXPECT_GT(st.passed_on_power.g, 0.0);
  EXPECT_GT(st.direct_power.g, 0.5 * st.emitted_power.g);
  EXPECT_GT(st.absorbed_power.g, 0.0);
  EXPECT_GT(caustic_power_fraction(st), 0.01);
  EXPECT_EQ(st.emitted, 50000u);
  for (const photon& p : result.map.photons()) {
    ASSERT_GT(glm::dot(p.incoming, p.normal), 0.0);
    ASSERT_NEAR(glm::length(p.incoming), 1.0, 1e-9);
    ASSERT_TRUE(p.surface <= 5 || p.surface == 8) << p.surface;  // the walls, the shiny ball
  }
}

TEST(CausticPhotons, GlassBallFocusesLightBelowIt) {
  // A point light high above a glass ball on the floor: the ball's focal
  // spot on the floor is far brighter than the direct light would be.
  scene s;
  const int floor = add_material(s, rgb(0.5));
  const int glass = add_glass(s);
  add_square(s, 20.0, 0.0, true, floor);
  surface ball;
  ball.geometry = sphere{vec3(0.0, 1.5, 0.0), 1.0, glass};
  s.surfaces.push_back(ball);
  s.lights.push_back({vec3(0.0, 8.0, 0.0), rgb(1000.0)});
  const ray_scene rays(s);
  const caustic_result result = caustic_photons(s, rays, photon_params{});
  // About 1200 photons reach the ball; paraxially they converge to y =
  // -0.45, in a spot of radius about 0.23 on the floor: some 400 W/m^2.
  const double direct = 1000.0 / (8.0 * 8.0);
  const rgb focus = result.map.irradiance_estimate(vec3(0.0), vec3(0, 1, 0), 0.5, 50);
  EXPECT_GT(focus.r, 10.0 * direct);
  // No caustic far to the side: nothing there came through the ball.
  EXPECT_EQ(result.map.irradiance_estimate(vec3(5.0, 0.0, 0.0), vec3(0, 1, 0), 0.5, 50), rgb(0.0));
}

TEST(CausticPhotons, SameSeedSameMapOnAnyNumberOfThreads) {
  const scene s = caustic_room();
  const ray_scene rays(s);
  photon_params params;
  params.photon_count = 20000;
  const caustic_result a = caustic_photons(s, rays, params);
  ASSERT_GT(a.map.size(), 100u);
  {
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const caustic_result b = caustic_photons(s, rays, params);
    EXPECT_TRUE(same_photons(a.map, b.map));
    EXPECT_EQ(a.stats.stored_power, b.stats.stored_power);
  }
  params.parallel = false;
  const caustic_result c = caustic_photons(s, rays, params);
  EXPECT_TRUE(same_photons(a.map, c.map));
  EXPECT_EQ(a.stats.escaped_power, c.stats.escaped_power);
  params.seed = 2;
  EXPECT_FALSE(same_photons(a.map, caustic_photons(s, rays, params).map));
}

TEST(CausticPhotons, QuadricEmittersAreCountedAsSkippedAndCancelStops) {
  scene s = caustic_room();
  const int light = add_material(s, rgb(0.0), rgb(1.0));
  surface glow;
  quadric q;  // x^2 + (y - 2)^2 + z^2 = 0.01: a small ball made as a quadric
  q.a = q.b = q.c = 1;
  q.h = -2;
  q.k = 4 - 0.01;
  q.box_min = vec3(-0.2, 1.8, -0.2);
  q.box_max = vec3(0.2, 2.2, 0.2);
  q.material = light;
  glow.geometry = q;
  s.surfaces.push_back(glow);
  const ray_scene rays(s);
  photon_params params;
  params.photon_count = 1000;
  EXPECT_EQ(caustic_photons(s, rays, params).stats.skipped_emitters, 1);
  photon_progress progress;
  progress.cancel = true;
  const caustic_result cancelled = caustic_photons(s, rays, params, &progress);
  EXPECT_TRUE(cancelled.stats.cancelled);
  EXPECT_EQ(cancelled.stats.emitted, 0u);
  EXPECT_TRUE(cancelled.map.empty());
}

}  // namespace
}  // namespace bounce
