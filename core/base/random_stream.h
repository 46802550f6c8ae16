// Reproducible random numbers. Every stream is seeded per work item (a
// pixel and its pass, a photon, a specular path, a pair of nodes), so that
// a result depends on the seed and the item alone and not on how the
// threads share the work. The hashes are fixed integer functions, the
// same on every platform.
#pragma once

#include <cstdint>

namespace bounce {

inline constexpr std::uint64_t golden_gamma = 0x9E3779B97F4A7C15ull;

// splitmix64's step: the finaliser of x + golden_gamma.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x += golden_gamma;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// MurmurHash3's 64-bit finaliser (the sky's sample jitter).
constexpr std::uint64_t murmur_mix64(std::uint64_t x) {
  x ^= x >> 33;
  x *= 0xff51afd7ed558ccdull;
  x ^= x >> 33;
  x *= 0xc4ceb9fe1a85ec53ull;
  x ^= x >> 33;
  return x;
}

// A double in [0, 1) from the high 53 bits.
constexpr double unit_interval(std::uint64_t bits) {
  return double(bits >> 11) * 0x1p-53;
}

// splitmix64 as a stream: each number mixes the state, which then moves
// on by golden_gamma.
struct random_stream {
  std::uint64_t state;
  explicit random_stream(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0)
      : state(seed * golden_gamma ^ (a + 0x632BE59BD9B4E019ull) * 0xBF58476D1CE4E5B9ull ^
              (b + 1) * 0x94D049BB133111EBull) {
    next_bits();
  }
  std::uint64_t next_bits() {
    const std::uint64_t bits = mix64(state);
    state += golden_gamma;
    return bits;
  }
  double uniform() { return unit_interval(next_bits()); }  // [0, 1)
};

// A stream that is its own hash chain: each number is the mix of the last
// (the hierarchical solver's and the form factors' per-pair jitter).
struct hash_chain {
  std::uint64_t state;
  double uniform() {
    state = mix64(state);
    return unit_interval(state);
  }
};

}  // namespace bounce
