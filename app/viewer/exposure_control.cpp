#include "viewer/exposure_control.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glad/gl.h>

#include "image/tonemap.h"

namespace bounce {
namespace {

constexpr double interval_seconds = 0.25;  // between measurements
constexpr double time_constant = 0.5;      // of the approach, in seconds
constexpr int stride = 4;                  // every 4th pixel of every 4th row is measured

}  // namespace

image read_view_radiance(int width, int height, const gl::display_settings& display, int stride) {
  stride = std::max(stride, 1);
  image out = uniform_image(std::max(width, 0) / stride, std::max(height, 0) / stride, rgb(0.0));
  if (out.width <= 0 || out.height <= 0) return out;
  std::vector<unsigned char> pixels(std::size_t(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  const bool filmic = display.curve == gl::tone_curve::filmic;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const unsigned char* p =
          &pixels[(std::size_t(height - 1 - y * stride) * width + x * stride) * 4];  // GL: bottom-up
      float* q = &out.pixels[(std::size_t(y) * out.width + x) * 3];
      for (int c = 0; c < 3; ++c) q[c] = float(display_to_linear(p[c] / 255.0, filmic) / display.exposure);
    }
  return out;
}

double adapted_exposure(double current, double target, double seconds) {
  const double from = std::log2(current), to = std::log2(target);
  return std::exp2(from + (to - from) * (1.0 - std::exp(-std::max(seconds, 0.0) / time_constant)));
}

bool exposure_control::update(int width, int height, gl::display_settings& display) {
  const auto now = clock_type::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (width <= 0 || height <= 0 || (measured_ && since < interval_seconds)) return false;
  const image view = read_view_radiance(width, height, display, stride);
  std::vector<rgb> radiance;
  radiance.reserve(std::size_t(view.width) * view.height);
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) radiance.push_back(view.at(x, y));
  if (radiance.empty()) return false;  // a view narrower than the stride
  const double target = std::clamp(auto_exposure(radiance), 1.0 / 65536.0, 65536.0);
  const double next = measured_ ? adapted_exposure(display.exposure, target, since) : target;
  last_ = now;
  measured_ = true;
  if (std::abs(std::log2(next / display.exposure)) < 0.02)
    return false;  // under a fiftieth of a stop: the same picture
  display.exposure = next;
  return true;
}

}  // namespace bounce
