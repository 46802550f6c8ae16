// Means per material against a reference: which pixel shows which
// material, and ratios that say a bias where one lies.
#include "measure/surface_means.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "measure/picture_judge.h"
#include "mesh_builders.h"
#include "trace/ray_scene.h"

namespace bounce {
namespace {

using test_support::add_material;
using test_support::add_polygon;

// Two unit squares side by side at z = 0 facing +z, "left" (x < 0) and
// "right" (x > 0), seen head-on from z = 3 by a 32 x 32 camera whose view
// they overfill from top to bottom and leave a gap of sky at the sides.
scene two_squares() {
  scene s;
  const int left = add_material(s, rgb(0.5)), right = add_material(s, rgb(0.5));
  s.materials[std::size_t(left)].name = "left";
  s.materials[std::size_t(right)].name = "right";
  add_polygon(s, {{-1, -1, 0}, {0, -1, 0}, {0, 1, 0}, {-1, 1, 0}}, left);
  add_polygon(s, {{0, -1, 0}, {1, -1, 0}, {1, 1, 0}, {0, 1, 0}}, right);
  s.view.eye = {0, 0, 3};
  s.view.target = {0, 0, 0};
  s.view.fov_y_degrees = 30.0;  // half-height tan(15 deg) * 3 = 0.80: the squares overfill it vertically
  s.view.width = 48;            // half-width 1.21: a strip of nothing on both sides
  s.view.height = 32;
  return s;
}

TEST(SurfaceMeans, EachPixelShowsTheMaterialItsCentreSees) {
  const scene s = two_squares();
  const ray_scene rays(s);
  const std::vector<int> m = material_per_pixel(s, s.view, rays);
  ASSERT_EQ(m.size(), 48u * 32u);
  const auto at = [&](int x, int y) { return m[std::size_t(y) * 48 + std::size_t(x)]; };
  for (int y : {0, 16, 31}) {
    EXPECT_EQ(at(0, y), -1) << y;  // beyond the squares
    EXPECT_EQ(at(12, y), 0) << y;  // left: x < 0 in the scene is the image's left
    EXPECT_EQ(at(35, y), 1) << y;
    EXPECT_EQ(at(47, y), -1) << y;
  }
}

TEST(SurfaceMeans, ABiasOnOneMaterialShowsOnlyThere) {
  const scene s = two_squares();
  const ray_scene rays(s);
  const std::vector<int> m = material_per_pixel(s, s.view, rays);
  image reference = uniform_image(48, 32, rgb(0.0));
  // A reference that varies across the picture; the test is 20% dark on
  // the left square and exact on the right one.
  for (std::size_t i = 0; i < m.size(); ++i)
    for (int ch = 0; ch < 3; ++ch) reference.pixels[3 * i + std::size_t(ch)] = float(0.1 + 0.01 * double(i % 48));
  image picture = reference;
  for (std::size_t i = 0; i < m.size(); ++i)
    if (m[i] == 0)
      for (int ch = 0; ch < 3; ++ch) picture.pixels[3 * i + std::size_t(ch)] *= 0.8f;
  // Excluded reference pixels (NaN) count for neither side.
  for (int ch = 0; ch < 3; ++ch)
    reference.pixels[3 * (16 * 48 + 12) + std::size_t(ch)] = std::numeric_limits<float>::quiet_NaN();
  const std::vector<surface_mean> means = surface_means(picture, reference, m, s);
  ASSERT_EQ(means.size(), 2u);
  EXPECT_EQ(means[0].material, "left");
  EXPECT_NEAR(means[0].ratio, 0.8, 1e-6);
  EXPECT_EQ(means[1].material, "right");
  EXPECT_NEAR(means[1].ratio, 1.0, 1e-6);
  std::size_t left = 0, right = 0;
  for (int v : m) {
    left += v == 0 ? 1 : 0;
    right += v == 1 ? 1 : 0;
  }
  EXPECT_EQ(means[0].pixels, left - 1);  // the excluded pixel
  EXPECT_EQ(means[1].pixels, right);
  // A material seen by too few pixels is left out.
  EXPECT_TRUE(surface_means(picture, reference, m, s, left + right).empty());
}

// The judge reports the means of the pictures it judges: a picture 10%
// bright everywhere is 1.1 on both squares.
TEST(SurfaceMeans, TheJudgeReportsThemPerPicture) {
  scene s = two_squares();
  // A lamp behind the camera, facing the squares.
  add_polygon(s, {{-1, -1, 4}, {-1, 1, 4}, {1, 1, 4}, {1, -1, 4}}, add_material(s, rgb(0.0), rgb(1.0)));
  bench_truth truth;
  truth.picture = path_reference(s, 16, 1);
  truth.exclude_above = 0.5;
  truth.downsample = 1;
  const picture_judge judge(s, s.view, truth);
  image brighter = truth.picture;
  for (float& v : brighter.pixels) v *= 1.1f;
  const picture_judge::verdict v = judge.judge(brighter);
  ASSERT_EQ(v.surfaces.size(), 2u);
  for (const surface_mean& mean : v.surfaces) EXPECT_NEAR(mean.ratio, 1.1, 1e-5) << mean.material;
  EXPECT_GE(v.error, 0.1 - 1e-6);  // the RMS of 10% of the picture over its mean
}

}  // namespace
}  // namespace bounce
