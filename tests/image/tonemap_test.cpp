// Display encoding: the sRGB transfer function and the automatic exposure.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "image/tonemap.h"

namespace bounce {
namespace {

TEST(Tonemap, SrgbTransferFunction) {
  EXPECT_EQ(linear_to_srgb(0.0), 0.0);
  EXPECT_NEAR(linear_to_srgb(1.0), 1.0, 1e-12);
  // Both pieces meet at the standard's break point.
  EXPECT_NEAR(linear_to_srgb(0.0031308), 0.04045, 1e-5);
  EXPECT_NEAR(linear_to_srgb(0.0031308 + 1e-12), 0.04045, 1e-5);
  // 18% grey encodes to about 46% (118 of 255).
  EXPECT_NEAR(linear_to_srgb(0.18), 0.4613, 1e-4);
  EXPECT_EQ(linear_to_srgb(-1.0), 0.0);  // clamped
  EXPECT_NEAR(linear_to_srgb(7.0), 1.0, 1e-12);
  // Monotone.
  for (int i = 1; i <= 1000; ++i) EXPECT_LT(linear_to_srgb((i - 1) / 1000.0), linear_to_srgb(i / 1000.0));
}

TEST(Tonemap, EightBitEncodingWithExposure) {
  EXPECT_EQ(to_srgb8(rgb(0.0), 1.0), glm::u8vec3(0));
  EXPECT_EQ(to_srgb8(rgb(1.0), 1.0), glm::u8vec3(255));
  EXPECT_EQ(to_srgb8(rgb(0.5), 2.0), glm::u8vec3(255));
  EXPECT_EQ(to_srgb8(rgb(0.18, 0.0, 100.0), 1.0), glm::u8vec3(118, 0, 255));
}

TEST(Tonemap, AutoExposureMapsThe95thPercentileTo08) {
  std::vector<rgb> radiance;
  for (int i = 1; i <= 100; ++i) radiance.push_back(rgb(i * 0.01));  // luminance = i / 100
  const double exposure = auto_exposure(radiance);
  EXPECT_NEAR(exposure * 0.95, 0.8, 0.8 * 0.011);  // the 95th value of 100
  EXPECT_EQ(auto_exposure(std::vector<rgb>{}), 1.0);
  EXPECT_EQ(auto_exposure(std::vector<rgb>(10, rgb(0.0))), 1.0);
  EXPECT_NEAR(luminance(rgb(1.0)), 1.0, 1e-12);
}

// The display encoding undone: every value the curves show below their top
// reads back to the linear value that made it.
TEST(Tonemap, DisplayEncodingReadsBack) {
  for (const double x : {0.0, 0.001, 0.01, 0.18, 0.5, 0.9}) {
    EXPECT_NEAR(display_to_linear(linear_to_srgb(x), false), x, 1e-9 + 1e-9 * x);
    EXPECT_NEAR(display_to_linear(linear_to_srgb(filmic_curve(x)), true), x, 1e-9 + 1e-9 * x);
  }
  for (const double x : {2.0, 5.0}) EXPECT_NEAR(display_to_linear(linear_to_srgb(filmic_curve(x)), true), x, 1e-6 * x);
  // At the top, the least value that shows so.
  EXPECT_DOUBLE_EQ(display_to_linear(1.0, false), 1.0);
  EXPECT_NEAR(filmic_curve(display_to_linear(1.0, true)), 1.0, 1e-12);
  EXPECT_NEAR(filmic_curve(0.18), 0.2668, 1e-4);  // Narkowicz's fit: mid grey shows at 0.27
}

}  // namespace
}  // namespace bounce
