#pragma once
// splitmix64 (Steele, Lea, Flood 2014): a fully specified random stream, unlike the standard
// library's distributions, whose output differs between implementations; bootstraps seeded with
// it give the same interval on every machine.
#include <cstddef>
#include <cstdint>

namespace lb {

struct SplitMix64 {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Modulo bias for n of a few thousand samples is below 1e-15: irrelevant here.
  size_t below(size_t n) { return size_t(next() % n); }
};

}  // namespace lb
