// Punctual lights (scene/lights.h): the spot's cone and its solid angle,
// the sun, and photon starts whose mean carries the light's power.
#include "scene/lights.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "base/random_stream.h"

namespace bounce {
namespace {

using std::numbers::pi;
constexpr double degree = pi / 180.0;

punctual_light spot(double inner_degrees, double outer_degrees) {
  punctual_light l;
  l.type = light_type::spot;
  l.position = vec3(0, 2, 0);
  l.intensity = rgb(10.0);
  l.direction = vec3(0, -1, 0);
  l.inner_cone = inner_degrees * degree;
  l.outer_cone = outer_degrees * degree;
  return l;
}

vec3 at_angle(double degrees) {
  return vec3(std::sin(degrees * degree), -std::cos(degrees * degree), 0.0);
}

TEST(Lights, SpotConeIsWholeInsideNoneOutsideAndSmoothBetween) {
  const punctual_light l = spot(20, 30);
  EXPECT_EQ(cone_share(l, at_angle(0)), 1.0);
  EXPECT_EQ(cone_share(l, at_angle(19.9)), 1.0);
  EXPECT_EQ(cone_share(l, at_angle(30.1)), 0.0);
  EXPECT_EQ(cone_share(l, vec3(0, 1, 0)), 0.0);
  // glTF's smooth edge: t^2, t linear in the cosine.
  const double c = std::cos(25 * degree), ci = std::cos(20 * degree), co = std::cos(30 * degree);
  const double t = (c - co) / (ci - co);
  EXPECT_NEAR(cone_share(l, at_angle(25)), t * t, 1e-12);
  punctual_light point = l;
  point.type = light_type::point;
  EXPECT_EQ(cone_share(point, vec3(0, 1, 0)), 1.0);
}

TEST(Lights, ConeSolidAngleIsTheIntegralOfTheShare) {
  // Narrow cones too, where the edge's width is held to 1e-3 in the cosine.
  for (const auto& [inner, outer] :
       {std::pair{0.0, 45.0}, {20.0, 30.0}, {29.0, 30.0}, {0.0, 90.0}, {1.0, 2.0}, {2.5, 3.0}, {0.0, 0.5}}) {
    const punctual_light l = spot(inner, outer);
    // Midpoint rule in the cosine: d omega = 2 pi d(cos).
    constexpr int n = 200000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double c = -1.0 + (i + 0.5) * 2.0 / n;
      const double s = std::sqrt(1.0 - c * c);
      sum += cone_share(l, vec3(s, -c, 0.0)) * 2.0 / n;
    }
    EXPECT_NEAR(cone_solid_angle(l), 2.0 * pi * sum, 1e-6) << inner << " " << outer;
  }
  punctual_light point;
  EXPECT_DOUBLE_EQ(cone_solid_angle(point), 4.0 * pi);
  EXPECT_EQ(emitted_power(point, 1.0), rgb(0.0));
  point.intensity = rgb(2.0);
  EXPECT_DOUBLE_EQ(emitted_power(point, 1.0).r, 8.0 * pi);
}

TEST(Lights, ArrivalFollowsInverseSquareConeAndSun) {
  const punctual_light l = spot(20, 30);
  const light_arrival below = light_at(l, vec3(0, 0, 0), 100.0);
  EXPECT_NEAR(below.irradiance.r, 10.0 / 4.0, 1e-12);
  EXPECT_EQ(below.shadow_end, l.position);
  EXPECT_NEAR(below.to_light.y, 1.0, 1e-12);
  EXPECT_EQ(light_at(l, vec3(3, 0, 0), 100.0).irradiance, rgb(0.0));  // 56 degrees off the axis
  punctual_light sun;
  sun.type = light_type::sun;
  sun.direction = glm::normalize(vec3(1, -2, 0));
  sun.intensity = rgb(3.0);
  const light_arrival a = light_at(sun, vec3(5, 0, 5), 10.0);
  EXPECT_EQ(a.irradiance, rgb(3.0));  // no fall-off
  EXPECT_NEAR(glm::length(a.to_light + sun.direction), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(a.shadow_end - vec3(5, 0, 5)), 10.0, 1e-12);
}

TEST(Lights, PhotonStartsCarryThePowerAndStayInTheCone) {
  const punctual_light l = spot(20, 30);
  random_stream rng(7, 0);
  constexpr int n = 200000;
  double weights = 0.0, inner_weights = 0.0;
  for (int i = 0; i < n; ++i) {
    const light_photon p = sample_light_photon(l, vec3(0.0), 5.0, rng.uniform(), rng.uniform());
    ASSERT_EQ(p.origin, l.position);
    ASSERT_GE(glm::dot(p.direction, l.direction), std::cos(30 * degree) - 1e-12);
    weights += p.weight;
    if (glm::dot(p.direction, l.direction) >= std::cos(20 * degree)) inner_weights += p.weight;
  }
  // The mean weight is 1: n photons of power P / n carry P.
  EXPECT_NEAR(weights / n, 1.0, 0.01);
  // The inner cone's share of the power: its solid angle over the weighted one.
  EXPECT_NEAR(inner_weights / n, 2.0 * pi * (1.0 - std::cos(20 * degree)) / cone_solid_angle(l), 0.01);

  punctual_light sun;
  sun.type = light_type::sun;
  sun.direction = glm::normalize(vec3(0, -1, 1));
  sun.intensity = rgb(1.0);
  const vec3 centre(1, 2, 3);
  EXPECT_NEAR(emitted_power(sun, 2.0).g, pi * 4.0, 1e-12);
  for (int i = 0; i < 1000; ++i) {
    const light_photon p = sample_light_photon(sun, centre, 2.0, rng.uniform(), rng.uniform());
    EXPECT_EQ(p.direction, sun.direction);
    EXPECT_EQ(p.weight, 1.0);
    // On the disc facing the light, outside the ball about the scene.
    const vec3 from_centre = p.origin - centre;
    EXPECT_NEAR(glm::dot(from_centre, sun.direction), -1.01 * 2.0, 1e-9);
    EXPECT_LE(glm::length(from_centre - glm::dot(from_centre, sun.direction) * sun.direction), 2.0 + 1e-9);
  }
}

}  // namespace
}  // namespace bounce
