#include "measure/surface_means.h"

#include <cmath>

#include "base/check.h"
#include "scene/camera_math.h"

namespace bounce {

std::vector<int> material_per_pixel(const scene& s, const camera& view, const ray_scene& rays) {
  BOUNCE_CHECK(view.width > 0 && view.height > 0);
  const camera_rays through(view);
  std::vector<int> out(std::size_t(view.width) * std::size_t(view.height), -1);
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const auto hit = rays.intersect(view.eye, through.direction(x + 0.5, y + 0.5));
      if (hit && hit->material >= 0 && std::size_t(hit->material) < s.materials.size())
        out[std::size_t(y) * std::size_t(view.width) + std::size_t(x)] = hit->material;
    }
  return out;
}

std::vector<surface_mean> surface_means(const image& picture, const image& reference, std::span<const int> material,
                                        const scene& s, std::size_t min_pixels) {
  BOUNCE_CHECK_EQ(picture.width, reference.width);
  BOUNCE_CHECK_EQ(picture.height, reference.height);
  BOUNCE_CHECK_EQ(material.size(), std::size_t(reference.width) * std::size_t(reference.height));
  struct sums {
    double picture = 0.0, reference = 0.0;
    std::size_t pixels = 0;
  };
  std::vector<sums> by(s.materials.size());
  for (std::size_t i = 0; i < material.size(); ++i) {
    const int m = material[i];
    if (m < 0) continue;
    double p = 0.0, r = 0.0;
    bool measured = true;
    for (int ch = 0; ch < 3; ++ch) {
      const double pv = picture.pixels[3 * i + std::size_t(ch)], rv = reference.pixels[3 * i + std::size_t(ch)];
      measured = measured && std::isfinite(pv) && std::isfinite(rv);
      p += pv;
      r += rv;
    }
    if (!measured) continue;
    sums& at = by[std::size_t(m)];
    at.picture += p;
    at.reference += r;
    ++at.pixels;
  }
  std::vector<surface_mean> out;
  for (std::size_t m = 0; m < by.size(); ++m) {
    if (by[m].pixels < min_pixels || !(by[m].reference > 0.0)) continue;
    out.push_back({s.materials[m].name, by[m].pixels, by[m].picture / by[m].reference});
  }
  return out;
}

}  // namespace bounce
