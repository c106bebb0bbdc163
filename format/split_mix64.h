// SplitMix64 (Steele, Lea, Flood 2014): a 64-bit state advanced by a constant
// and finalized by a bijective mix; passes BigCrush, period 2^64. Our own
// generator and our own mapping to doubles, so random samples (the metric's,
// the remesher's fit) are the same on every platform and standard library.
#pragma once

#include <cstdint>

namespace srcodec {

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}

  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  uint64_t state_;
};

}  // namespace srcodec
