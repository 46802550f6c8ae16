// The photon map's density estimate against photons laid out on a grid of
// known power density.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "trace/photon_map.h"

namespace bounce {
namespace {

using std::numbers::pi;

constexpr double spacing = 0.1;  // grid step on the floor y = 0
constexpr double grid_power = 0.02;
constexpr int half = 60;  // grid from -6 to 6

// Photons on the floor at every grid point, landed from above: power
// density grid_power / spacing^2 = 2 W/m^2. `other_side` adds a second,
// much brighter layer just below, on the underside of a thin floor
// (normal down, arrived from below), and a layer on the top side that
// arrived from below (through the floor: it must not count either).
std::vector<photon> grid_photons(bool other_side) {
  std::vector<photon> out;
  for (int i = -half; i <= half; ++i)
    for (int j = -half; j <= half; ++j) {
      const vec3 p(i * spacing, 0.0, j * spacing);
      out.push_back({p, glm::normalize(vec3(0.3, 1.0, -0.2)), rgb(grid_power), vec3(0, 1, 0), 0});
      if (other_side) {
        out.push_back({p - vec3(0, 1e-4, 0), vec3(0, -1, 0), rgb(100.0), vec3(0, -1, 0), 1});
        out.push_back({p + vec3(0.01, 0, 0.01), vec3(0, -1, 0), rgb(100.0), vec3(0, 1, 0), 0});
      }
    }
  return out;
}

// Brute force: the grid points within r of q.
int grid_count(const vec3& q, double r) {
  int n = 0;
  for (int i = -half; i <= half; ++i)
    for (int j = -half; j <= half; ++j) {
      const vec3 d = vec3(i * spacing, 0.0, j * spacing) - q;
      n += glm::dot(d, d) <= r * r;
    }
  return n;
}

const vec3 up(0, 1, 0);
const vec3 query(0.013, 0.0, 0.027);  // off the grid, so that no photon lies at exactly the radius
const double density = grid_power / (spacing * spacing);

TEST(PhotonMap, BoxEstimateIsThePowerInTheDiscOverItsArea) {
  const photon_map map(grid_photons(false));
  EXPECT_EQ(map.size(), std::size_t((2 * half + 1) * (2 * half + 1)));
  for (const double r : {0.35, 1.05, 2.05}) {
    const photon_estimate e = map.estimate(query, up, r, 1000000, photon_filter::box);
    const int n = grid_count(query, r);
    EXPECT_EQ(e.photons, n) << r;
    EXPECT_EQ(e.radius, r);
    EXPECT_NEAR(e.irradiance.g, n * grid_power / (pi * r * r), 1e-12) << r;
  }
  // A disc of 20 grid steps holds its area's worth of photons to the
  // lattice-point error of a circle (Gauss): within 1 %.
  EXPECT_NEAR(map.irradiance_estimate(query, up, 2.05, 1000000, photon_filter::box).r, density, 0.01 * density);
}

TEST(PhotonMap, ConeFilterIsUnbiasedOnAUniformDensity) {
  const photon_map map(grid_photons(false));
  const rgb e = map.irradiance_estimate(query, up, 2.05, 1000000, photon_filter::cone);
  EXPECT_NEAR(e.b, density, 0.01 * density);
  // Unnormalised, the cone would give 1 - 2 / (3 k) of it: 39 % less.
  EXPECT_GT(e.b, 0.9 * density);
}

TEST(PhotonMap, PhotonsOnTheOtherSideOrFromBehindDoNotCount) {
  const photon_map alone(grid_photons(false));
  const photon_map both(grid_photons(true));
  EXPECT_EQ(both.size(), 3 * alone.size());
  for (const photon_filter f : {photon_filter::box, photon_filter::cone}) {
    EXPECT_EQ(both.irradiance_estimate(query, up, 1.05, 1000000, f),
              alone.irradiance_estimate(query, up, 1.05, 1000000, f));
    // The k nearest are the k nearest that count: the layers 1e-4 away
    // take none of their places.
    const photon_estimate a = alone.estimate(query, up, 1.05, 40, f), b = both.estimate(query, up, 1.05, 40, f);
    EXPECT_EQ(b.photons, 40);
    EXPECT_EQ(b.radius, a.radius);
    EXPECT_EQ(b.irradiance, a.irradiance);
  }
  // Seen from below, only the underside's photons count.
  const photon_estimate below = both.estimate(query - vec3(0, 1e-4, 0), -up, 1.05, 1000000, photon_filter::box);
  EXPECT_EQ(below.photons, grid_count(query, 1.05));
  EXPECT_NEAR(below.irradiance.r, below.photons * 100.0 / (pi * 1.05 * 1.05), 1e-9);
  // A wall meeting the floor (normal at 90 degrees) does not count either.
  EXPECT_EQ(alone.estimate(query, vec3(1, 0, 0), 1.05, 1000000).photons, 0);
}

TEST(PhotonMap, AParallelSurfaceNearbyLendsNoneOfItsPhotons) {
  // The grid as a floor, and a table top 0.3 above it (the same photons
  // moved up, ten times brighter). From the table, the search is a disc:
  // the floor's photons, 0.3 off its plane, do not count, even when they
  // are among the nearest in space; nor the table's from the floor.
  std::vector<photon> photons = grid_photons(false);
  const std::size_t floor_count = photons.size();
  for (std::size_t i = 0; i < floor_count; ++i) {
    photon p = photons[i];
    p.position.y += 0.3;
    p.power *= 10.0;
    photons.push_back(p);
  }
  const photon_map both(std::move(photons));
  const photon_map floor(grid_photons(false));
  const vec3 on_table = query + vec3(0, 0.3, 0);
  for (const double r : {0.35, 1.05}) {
    const photon_estimate table = both.estimate(on_table, up, r, 1000000, photon_filter::box);
    EXPECT_EQ(table.photons, grid_count(query, r)) << r;  // the table's own, and no more
    EXPECT_NEAR(table.irradiance.r, 10.0 * grid_count(query, r) * grid_power / (pi * r * r), 1e-9) << r;
    EXPECT_EQ(both.estimate(query, up, r, 1000000, photon_filter::box).irradiance,
              floor.estimate(query, up, r, 1000000, photon_filter::box).irradiance);
  }
  // Photons near the plane still count: a surface curving away from it by
  // 0.2 at distance 1 (slope 0.2 at most, under the limit).
  std::vector<photon> curved = grid_photons(false);
  int within = 0;
  for (photon& p : curved) {
    p.position.y = 0.2 * glm::dot(p.position, p.position);
    within += glm::length(p.position - query) <= 1.0;
  }
  EXPECT_GT(within, 300);
  EXPECT_EQ(photon_map(curved).estimate(query, up, 1.0, 1000000, photon_filter::box).photons, within);
}

TEST(PhotonMap, KNearestShrinkTheRadiusToTheKthPhoton) {
  const photon_map map(grid_photons(false));
  std::vector<double> distances;
  for (int i = -half; i <= half; ++i)
    for (int j = -half; j <= half; ++j) distances.push_back(glm::length(vec3(i * spacing, 0.0, j * spacing) - query));
  std::sort(distances.begin(), distances.end());
  for (const int k : {1, 8, 50, 300}) {
    const photon_estimate e = map.estimate(query, up, 5.0, k, photon_filter::box);
    EXPECT_EQ(e.photons, k);
    EXPECT_NEAR(e.radius, distances[std::size_t(k - 1)], 1e-12) << k;
    EXPECT_NEAR(e.irradiance.g, k * grid_power / (pi * e.radius * e.radius), 1e-9) << k;
  }
  // Fewer than k within the radius: the radius stays.
  const photon_estimate few = map.estimate(query, up, 0.12, 50, photon_filter::box);
  EXPECT_EQ(few.photons, grid_count(query, 0.12));
  EXPECT_EQ(few.radius, 0.12);
  // Many photons: the k-nearest estimate tends to the density.
  EXPECT_NEAR(map.irradiance_estimate(query, up, 5.0, 2000, photon_filter::box).g, density, 0.02 * density);
}

TEST(PhotonMap, EmptyMapEstimatesNothingAndMovesKeepTheTree) {
  const photon_map empty;
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.irradiance_estimate(query, up, 1.0, 10), rgb(0.0));
  photon_map a(grid_photons(false));
  const rgb before = a.irradiance_estimate(query, up, 1.05, 100);
  photon_map b(std::move(a));
  EXPECT_EQ(b.irradiance_estimate(query, up, 1.05, 100), before);
  EXPECT_NEAR(b.total_power().r, grid_power * b.size(), 1e-9);
}

}  // namespace
}  // namespace bounce
