#include "image/pass_blend.h"

#include <algorithm>

#include "base/check.h"
#include "image/tonemap.h"

namespace bounce {
namespace {

double luminance_at(const image& img, std::size_t pixel) {
  return luminance(rgb(img.pixels[3 * pixel], img.pixels[3 * pixel + 1], img.pixels[3 * pixel + 2]));
}

// The mean over a window of 2 radius + 1 (clipped at the ends) along
// `lines` lines of `length` values, value i of line l at l * across + i * along.
std::vector<double> line_means(const std::vector<double>& values, int lines, int length, std::size_t across,
                               std::size_t along, int radius) {
  std::vector<double> out(values.size());
  for (int l = 0; l < lines; ++l)
    for (int i = 0; i < length; ++i) {
      const int lo = std::max(0, i - radius), hi = std::min(length - 1, i + radius);
      double sum = 0.0;
      for (int k = lo; k <= hi; ++k) sum += values[l * across + k * along];
      out[l * across + i * along] = sum / (hi - lo + 1);
    }
  return out;
}

// The mean over a (2 radius + 1)^2 window (clipped at the borders): along
// the rows, then along the columns.
std::vector<double> box_mean(const std::vector<double>& values, int width, int height, int radius) {
  const std::vector<double> across = line_means(values, height, width, std::size_t(width), 1, radius);
  return line_means(across, width, height, 1, std::size_t(width), radius);
}

}  // namespace

void add_pass(pass_sums& sums, const image& pass) {
  if (sums.passes == 0) {
    sums.sum = uniform_image(pass.width, pass.height, rgb(0.0));
    sums.luminance_squares.assign(std::size_t(pass.width) * pass.height, 0.0);
  }
  BOUNCE_CHECK(pass.width == sums.sum.width && pass.height == sums.sum.height);
  for (std::size_t i = 0; i < sums.sum.pixels.size(); ++i) sums.sum.pixels[i] += pass.pixels[i];
  for (std::size_t p = 0; p < sums.luminance_squares.size(); ++p) {
    const double l = luminance_at(pass, p);
    sums.luminance_squares[p] += l * l;
  }
  ++sums.passes;
}

image pass_mean(const pass_sums& sums) {
  image mean = sums.sum;
  for (float& v : mean.pixels) v /= float(std::max(1, sums.passes));
  return mean;
}

image blend_passes_with_live(const image& live, const pass_sums& sums, int radius) {
  const image mean = pass_mean(sums);
  if (live.pixels.empty()) return mean;
  BOUNCE_CHECK(live.width == mean.width && live.height == mean.height);
  if (sums.passes < 2) return live;
  const int width = mean.width, height = mean.height;
  const double n = sums.passes;
  std::vector<double> difference(std::size_t(width) * height), noise(difference.size());
  for (std::size_t p = 0; p < difference.size(); ++p) {
    const double m = luminance_at(mean, p), d = m - luminance_at(live, p);
    const double variance = std::max(0.0, sums.luminance_squares[p] / n - m * m) * n / (n - 1.0);
    difference[p] = d * d;
    noise[p] = variance / n;
  }
  const std::vector<double> d2 = box_mean(difference, width, height, radius);
  const std::vector<double> s2 = box_mean(noise, width, height, radius);
  image out = live;
  for (std::size_t p = 0; p < d2.size(); ++p) {
    const double bias = std::max(0.0, d2[p] - s2[p]);
    const double w = bias + s2[p] > 0.0 ? bias / (bias + s2[p]) : 0.0;
    for (int c = 0; c < 3; ++c) {
      float& v = out.pixels[3 * p + c];
      v = float(v + w * (mean.pixels[3 * p + c] - v));
    }
  }
  return out;
}

}  // namespace bounce
