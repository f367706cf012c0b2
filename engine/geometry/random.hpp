// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A small, portable pseudo-random generator for reproducible joint patterns.
//
// std::mt19937 is portable but std::normal_distribution (and the other
// distributions) are not: libstdc++, libc++ and MSVC draw different numbers
// from the same engine. A user's seed must give the same blocks everywhere,
// so the whole chain is written out here: SplitMix64 (Steele, Lea & Flood,
// "Fast splittable pseudorandom number generators", OOPSLA 2014) for the bits,
// 53-bit uniforms, and Marsaglia's polar method for normals.
#include <cmath>
#include <cstdint>
#include <initializer_list>

namespace dda::geometry {

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  // Uniform in [0, 1) with 53 random bits (exactly representable).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

  // Standard normal by Marsaglia's polar method. Uses only +, *, sqrt (IEEE
  // correctly rounded) and log; the rejection loop ends with probability 1
  // (acceptance rate π/4 per try).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u, v, s;
    do {
      u = 2.0 * uniform() - 1.0;
      v = 2.0 * uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double scale = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * scale;
    has_spare_ = true;
    return u * scale;
  }

 private:
  std::uint64_t state_;
  bool has_spare_ = false;
  double spare_ = 0;
};

// Derives an independent stream seed from a user seed and a path of integers
// (set index, line index, ...), so each joint line draws from its own stream
// and its numbers do not depend on how many other lines were generated.
inline std::uint64_t derive_seed(std::initializer_list<std::uint64_t> parts) {
  std::uint64_t h = 0x243F6A8885A308D3ull;  // digits of π: any fixed start will do
  for (std::uint64_t p : parts) {
    SplitMix64 mix(h ^ p);
    h = mix.next();
  }
  return h;
}

}  // namespace dda::geometry
