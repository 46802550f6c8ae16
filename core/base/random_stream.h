// splitmix64: small, fast, and seeded per work item (a pixel and its pass,
// a photon, a specular path), so that a result depends on the seed and the
// item alone and not on how the threads share the work.
#pragma once

#include <cstdint>

namespace bounce {

struct random_stream {
  std::uint64_t state;
  explicit random_stream(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0)
      : state(seed * 0x9E3779B97F4A7C15ull ^ (a + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull ^
              (b + 1) * 0x94D049BB133111EBull) {
    next_bits();
  }
  std::uint64_t next_bits() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next_bits() >> 11) * 0x1p-53; }  // [0, 1)
};

}  // namespace bounce
