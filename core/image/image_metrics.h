// Error measures between pictures in linear radiance, for the tests, the
// speed-against-error measurements and adaptive anti-aliasing. Pixels set
// to NaN are excluded from every measure (see exclude_pixels).
#pragma once

#include <vector>

#include "image/image.h"

namespace bounce {

// Box-filters blocks of factor x factor pixels (the edges' partial blocks
// are dropped; a block with an excluded pixel is excluded). Discounts edge
// aliasing and noise when comparing methods.
image downsample(const image& img, int factor);

// Pixels whose luminance differs from a 4-neighbour's by more than
// `contrast` in |a - b| / (a + b): silhouettes, shadow and texture edges.
std::vector<bool> contrast_edges(const image& img, double contrast);

// Pixels with a channel above `radiance`: emitters seen directly.
std::vector<bool> bright_pixels(const image& img, double radiance);

// Sets the marked pixels, and those within `grow` pixels of them, to NaN.
void exclude_pixels(image& img, const std::vector<bool>& marked, int grow);

// Mean over the pixels and channels left.
double mean_radiance(const image& img);

// Root-mean-square difference over pixels and channels, divided by the
// reference's mean: an error relative to the picture's brightness that dark
// pixels cannot blow up. 0 for identical images; sizes must match.
double relative_rmse(const image& test, const image& reference);

// Mean and largest of |test - reference| / reference over pixels and
// channels, reference values below `floor` x the reference mean counted
// as that floor.
double mean_relative_error(const image& test, const image& reference, double floor = 0.01);
double max_relative_error(const image& test, const image& reference, double floor = 0.01);

}  // namespace bounce
