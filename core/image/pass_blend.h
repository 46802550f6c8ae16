// Passes of a noisy estimator (the still's integrator, a few samples a
// pixel each) shown over a smooth but possibly biased picture of the same
// view (the live Gouraud view). Early passes are noisier than the live
// picture; their mean only pays where it differs from the live picture by
// more than its own noise (a shadow the mesh missed, a texture, a
// highlight). Per pixel, the live picture moves towards the mean by
//
//     w = bias^2 / (bias^2 + noise^2),  bias^2 = max(0, (mean - live)^2 - noise^2),
//
// with noise^2 the variance of the mean (the passes' luminance variance over
// their count), both averaged over a small window so that the weight is
// not itself noise. This is the blend that minimises the expected squared
// error when the bias and the noise are known; as passes accumulate the
// noise falls and w goes to 1 wherever the live picture is wrong, while
// where the live picture is right it stays, smooth, from the first pass.
// A bias smaller than the noise stays: it costs less than the noise would.
#pragma once

#include <vector>

#include "image/image.h"

namespace bounce {

// Per pixel: the sum of the passes' colours and of their squared luminance.
struct pass_sums {
  image sum;
  std::vector<double> luminance_squares;
  int passes = 0;
};

// Adds one pass (the size of the first one added).
void add_pass(pass_sums& sums, const image& pass);

// The mean of the passes so far.
image pass_mean(const pass_sums& sums);

// The picture to show: `live` (same size) moved towards the passes' mean by
// the weight above, its terms averaged over (2 radius + 1)^2 pixels. With
// fewer than 2 passes the noise is unknown, so the live picture is shown;
// with no live picture (empty), the mean.
image blend_passes_with_live(const image& live, const pass_sums& sums, int radius = 2);

}  // namespace bounce
