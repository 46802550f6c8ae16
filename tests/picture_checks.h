// Comparing pictures written by the bounce command in tests.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "image/image.h"

namespace bounce::test_support {

// Mean absolute difference of two 8-bit pictures of one size, over 10 x 10
// blocks (the blocks' means compared, so that sample noise averages out),
// in levels of 255; infinite when they cannot be compared.
inline double block_difference(const std::string& a_path, const std::string& b_path) {
  int w = 0, h = 0, bw = 0, bh = 0;
  std::vector<unsigned char> a, b;
  std::string error;
  EXPECT_TRUE(read_png_rgb8(a_path, w, h, a, error)) << error;
  EXPECT_TRUE(read_png_rgb8(b_path, bw, bh, b, error)) << error;
  if (w != bw || h != bh || w < 10 || h < 10) return INFINITY;
  double sum = 0.0;
  int count = 0;
  for (int by = 0; by + 10 <= h; by += 10)
    for (int bx = 0; bx + 10 <= w; bx += 10) {
      double da = 0.0, db = 0.0;
      for (int y = by; y < by + 10; ++y)
        for (int x = bx; x < bx + 10; ++x)
          for (int c = 0; c < 3; ++c) {
            da += a[(std::size_t(y) * w + x) * 3 + c];
            db += b[(std::size_t(y) * w + x) * 3 + c];
          }
      sum += std::abs(da - db) / 300.0;
      ++count;
    }
  return sum / count;
}

}  // namespace bounce::test_support
