// Deterministic CPU random numbers for systems: PCG32 (O'Neill 2014, XSH-RR output, 64-bit
// state). Seedable, with independent streams, and splittable by key (per system, per entity)
// so a parallel frame draws the same numbers as a serial one. Per-pixel GPU numbers live in
// shaders/shared/rng.h; this one is for the CPU side only.
#pragma once

#include <cstdint>

namespace lantern {

// SplitMix64 finaliser: a strong 64-bit mix used to derive seeds and streams from keys.
constexpr std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

class Rng {
 public:
  constexpr explicit Rng(std::uint64_t seed = 1, std::uint64_t stream = 0) { reseed(seed, stream); }

  constexpr void reseed(std::uint64_t seed, std::uint64_t stream = 0) {
    seed_ = seed;
    stream_ = stream;
    inc_ = (stream << 1u) | 1u;  // the increment must be odd
    state_ = 0;
    next_u32();
    state_ += seed;
    next_u32();
  }

  // A generator for `key` (a system name hash, an entity's bits, ...) that depends only on this
  // generator's seed and stream, never on how many numbers it has drawn: split() gives the same
  // child before and after any draws, whichever thread asks.
  constexpr Rng split(std::uint64_t key) const {
    return Rng(mix64(seed_ ^ mix64(key + stream_)), mix64(key) ^ stream_);
  }

  constexpr std::uint32_t next_u32() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  // Uniform in [0, 1): 24 random bits fill the float mantissa exactly; 1.0 is never returned.
  constexpr float next_float() { return static_cast<float>(next_u32() >> 8u) * (1.0f / 16777216.0f); }

  constexpr float uniform(float lo, float hi) { return lo + (hi - lo) * next_float(); }

  // Uniform in [0, bound) without modulo bias (rejection of the short final interval).
  constexpr std::uint32_t bounded(std::uint32_t bound) {
    if (bound <= 1u) return 0u;
    const std::uint32_t threshold = (0u - bound) % bound;
    for (;;) {
      const std::uint32_t r = next_u32();
      if (r >= threshold) return r % bound;
    }
  }

  constexpr std::uint64_t seed() const { return seed_; }
  constexpr std::uint64_t stream() const { return stream_; }

 private:
  std::uint64_t state_ = 0;
  std::uint64_t inc_ = 1;
  std::uint64_t seed_ = 0;
  std::uint64_t stream_ = 0;
};

// FNV-1a of a name: a stable key for Rng::split from a system or entity name.
constexpr std::uint64_t hash_name(const char* s) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (; *s != '\0'; ++s) h = (h ^ static_cast<unsigned char>(*s)) * 0x100000001b3ull;
  return h;
}

}  // namespace lantern
