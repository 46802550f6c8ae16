// Mean radiance per material, a picture against its reference: where a
// solution is biased (a whole ceiling dark) rather than noisy, which one
// error over the picture cannot tell apart. The primary ray through each
// pixel's centre says which material the pixel shows; the pixels the
// reference leaves out (NaN: emitters and their ring) are left out here.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "image/image.h"
#include "scene/scene.h"
#include "trace/ray_scene.h"

namespace bounce {

struct surface_mean {
  std::string material;
  std::size_t pixels = 0;  // measured pixels that show it
  double ratio = 0.0;      // the picture's mean radiance over them / the reference's
};

// The material seen through each pixel's centre of `view` at its size
// (row-major, top row first, as the tracers store pictures); -1 where the
// ray leaves the scene.
std::vector<int> material_per_pixel(const scene& s, const camera& view, const ray_scene& rays);

// The mean of every material shown by at least `min_pixels` measured
// pixels, in the scene's material order. Sizes must match; `reference`
// must be bright somewhere on a material for its ratio to be finite.
std::vector<surface_mean> surface_means(const image& picture, const image& reference, std::span<const int> material,
                                        const scene& s, std::size_t min_pixels = 64);

}  // namespace bounce
