// The window's automatic exposure, on unless the user sets one: a few
// times a second the view is read back, its pixels are turned back into
// radiance, and the exposure moves, over about half a second, towards the
// one that maps the 95th percentile of the visible radiance to 0.8 (the
// rule of auto_exposure in image/tonemap.h, which PLY output uses too).
// Bright parts keep their detail; a dim room opens bright enough to see.
#pragma once

#include <chrono>

#include "image/image.h"
#include "render/mesh_renderer.h"

namespace bounce {

// The current framebuffer's `width` x `height` pixels at the origin (the
// view, drawn, before the panel) as radiance: the display's tone curve and
// exposure undone, to 8-bit precision. Row 0 at the top. With `stride` > 1,
// only every stride-th pixel of every stride-th row, in a picture that
// much smaller.
image read_view_radiance(int width, int height, const gl::display_settings& display, int stride = 1);

// `current` moved towards `target` (both exposures) as an exponential
// approach in stops with a time constant of half a second, over `seconds`.
double adapted_exposure(double current, double target, double seconds);

class exposure_control {
 public:
  // When due, reads back the current framebuffer's `width` x `height`
  // pixels at the origin (the view, drawn, before the panel) and moves
  // `display.exposure`; the first measurement after start() jumps there.
  // Returns whether the exposure changed.
  bool update(int width, int height, gl::display_settings& display);
  // The next measurement sets the exposure at once (a new scene, or the
  // first light after the preview).
  void start() { measured_ = false; }

 private:
  using clock_type = std::chrono::steady_clock;
  clock_type::time_point last_{};
  bool measured_ = false;
};

}  // namespace bounce
