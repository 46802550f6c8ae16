// Passes blended with the live picture: the live one where it is right,
// the passes' mean where it is wrong, by how far each is from the truth.
#include "image/pass_blend.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "base/random_stream.h"

namespace bounce {
namespace {

constexpr int size = 64;

// A smooth ramp with a shadow (a quarter as bright) in the square
// [16, 40)^2, which the live picture misses.
double truth_at(int x, int y, bool with_shadow) {
  const double ramp = 0.5 + 0.5 * double(x + y) / (2 * size);
  const bool shadow = with_shadow && x >= 16 && x < 40 && y >= 16 && y < 40;
  return shadow ? 0.25 * ramp : ramp;
}

image picture(bool with_shadow) {
  image img = uniform_image(size, size, rgb(0.0));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (int c = 0; c < 3; ++c) img.pixels[(std::size_t(y) * size + x) * 3 + c] = float(truth_at(x, y, with_shadow));
  return img;
}

// One pass: the truth times (1 + noise), the noise uniform with standard deviation 0.4.
image noisy_pass(std::uint64_t seed) {
  random_stream random(seed, 7);
  image img = picture(true);
  for (std::size_t p = 0; p < img.pixels.size() / 3; ++p) {
    const float factor = float(1.0 + 0.4 * std::sqrt(12.0) * (random.uniform() - 0.5));
    for (int c = 0; c < 3; ++c) img.pixels[3 * p + c] *= factor;
  }
  return img;
}

// RMS error against the truth over the shadow, or over the rest away from its edge.
double rms_error(const image& img, bool in_shadow) {
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool inside = x >= 16 && x < 40 && y >= 16 && y < 40;
      const bool far_outside = x < 12 || x >= 44 || y < 12 || y >= 44;
      if (in_shadow ? !inside : !far_outside) continue;
      const double e = img.at(x, y).r - truth_at(x, y, true);
      sum += e * e;
      ++count;
    }
  return std::sqrt(sum / count);
}

TEST(PassBlend, LiveWhereItIsRightPassesWhereItIsWrong) {
  const image live = picture(false);
  pass_sums sums;
  for (int n = 1; n <= 64; ++n) {
    add_pass(sums, noisy_pass(std::uint64_t(n)));
    if (n != 4 && n != 16 && n != 64) continue;
    const image mean = pass_mean(sums), shown = blend_passes_with_live(live, sums);
    const double open_mean = rms_error(mean, false), open_shown = rms_error(shown, false);
    const double shadow_live = rms_error(live, true), shadow_mean = rms_error(mean, true),
                 shadow_shown = rms_error(shown, true);
    std::printf("  %2d passes: open: mean %.4f shown %.4f; shadow: live %.4f mean %.4f shown %.4f\n", n, open_mean,
                open_shown, shadow_live, shadow_mean, shadow_shown);
    // In the open the live picture is right: the blend keeps most of it.
    EXPECT_LT(open_shown, 0.5 * open_mean) << n;
    // In the shadow it is wrong by far more than the noise: the blend follows the passes.
    EXPECT_LT(shadow_shown, 0.3 * shadow_live) << n;
    EXPECT_LT(shadow_shown, 1.5 * shadow_mean) << n;
  }
}

TEST(PassBlend, OnePassShowsTheLivePictureAndNoLivePictureTheMean) {
  const image live = picture(false);
  pass_sums sums;
  add_pass(sums, noisy_pass(1));
  EXPECT_EQ(blend_passes_with_live(live, sums).pixels, live.pixels);
  add_pass(sums, noisy_pass(2));
  EXPECT_EQ(blend_passes_with_live(image{}, sums).pixels, pass_mean(sums).pixels);
}

}  // namespace
}  // namespace bounce
