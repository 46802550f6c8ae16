#include "image/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "image/tonemap.h"

namespace bounce {
namespace {

// Calls f(test, reference) for every channel value both images keep.
template <typename visit>
bool for_each_pair(const image& test, const image& reference, visit&& f) {
  if (test.pixels.size() != reference.pixels.size() || test.width != reference.width) return false;
  for (std::size_t i = 0; i < test.pixels.size(); ++i)
    if (!std::isnan(test.pixels[i]) && !std::isnan(reference.pixels[i]))
      f(double(test.pixels[i]), double(reference.pixels[i]));
  return true;
}

}  // namespace

image downsample(const image& img, int factor) {
  image out;
  factor = std::max(factor, 1);
  out.width = img.width / factor;
  out.height = img.height / factor;
  out.pixels.assign(std::size_t(out.width) * out.height * 3, 0.0f);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      rgb sum(0.0);
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i) sum += img.at(x * factor + i, y * factor + j);  // NaN stays NaN
      sum /= double(factor) * factor;
      for (int c = 0; c < 3; ++c) out.pixels[(std::size_t(y) * out.width + x) * 3 + c] = float(sum[c]);
    }
  return out;
}

std::vector<bool> contrast_edges(const image& img, double contrast) {
  std::vector<double> lum(std::size_t(img.width) * img.height);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) lum[std::size_t(y) * img.width + x] = luminance(img.at(x, y));
  auto differs = [&](std::size_t a, std::size_t b) {
    const double sum = lum[a] + lum[b];
    return sum > 0.0 && std::abs(lum[a] - lum[b]) / sum > contrast;
  };
  std::vector<bool> out(lum.size(), false);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::size_t i = std::size_t(y) * img.width + x;
      out[i] = (x > 0 && differs(i, i - 1)) || (x + 1 < img.width && differs(i, i + 1)) ||
               (y > 0 && differs(i, i - img.width)) || (y + 1 < img.height && differs(i, i + img.width));
    }
  return out;
}

std::vector<bool> bright_pixels(const image& img, double radiance) {
  std::vector<bool> out(std::size_t(img.width) * img.height);
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = std::max({img.pixels[3 * i], img.pixels[3 * i + 1], img.pixels[3 * i + 2]}) > radiance;
  return out;
}

void exclude_pixels(image& img, const std::vector<bool>& marked, int grow) {
  const std::vector<bool> original = marked;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      bool hit = false;
      for (int j = std::max(0, y - grow); j <= std::min(img.height - 1, y + grow) && !hit; ++j)
        for (int i = std::max(0, x - grow); i <= std::min(img.width - 1, x + grow) && !hit; ++i)
          hit = original[std::size_t(j) * img.width + i];
      if (hit)
        for (int c = 0; c < 3; ++c)
          img.pixels[(std::size_t(y) * img.width + x) * 3 + c] = std::numeric_limits<float>::quiet_NaN();
    }
}

double mean_radiance(const image& img) {
  double sum = 0.0;
  std::size_t n = 0;
  for (float v : img.pixels)
    if (!std::isnan(v)) {
      sum += v;
      ++n;
    }
  return n ? sum / double(n) : 0.0;
}

double relative_rmse(const image& test, const image& reference) {
  double sum = 0.0;
  std::size_t n = 0;
  if (!for_each_pair(test, reference, [&](double t, double r) {
        sum += (t - r) * (t - r);
        ++n;
      }))
    return INFINITY;
  const double mean = mean_radiance(reference);
  return n && mean > 0.0 ? std::sqrt(sum / double(n)) / mean : INFINITY;
}

double mean_relative_error(const image& test, const image& reference, double floor) {
  const double smallest = floor * mean_radiance(reference);
  double sum = 0.0;
  std::size_t n = 0;
  if (!for_each_pair(test, reference, [&](double t, double r) {
        sum += std::abs(t - r) / std::max(r, smallest);
        ++n;
      }))
    return INFINITY;
  return n ? sum / double(n) : INFINITY;
}

double max_relative_error(const image& test, const image& reference, double floor) {
  const double smallest = floor * mean_radiance(reference);
  double worst = 0.0;
  if (!for_each_pair(test, reference,
                     [&](double t, double r) { worst = std::max(worst, std::abs(t - r) / std::max(r, smallest)); }))
    return INFINITY;
  return worst;
}

}  // namespace bounce
