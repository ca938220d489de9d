// Per-pixel random numbers shared by GPU and CPU: a PCG hash seeds one 32-bit state per
// (pixel, frame, seed, pass); each draw is a PCG-RXS-M-XS step. Same inputs, same numbers on
// both sides, so CPU tests replay exactly what a shader draws.
#ifndef LANTERN_SHARED_RNG_H
#define LANTERN_SHARED_RNG_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// One PCG-RXS-M-XS round (O'Neill 2014) used as a 32-bit hash (Jarzynski & Olano 2020).
LANTERN_FUNC uint pcg_hash(uint x) {
  uint state = x * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Seeds a stream. `pass` separates the streams of different passes in one frame (e.g. initial
// candidates vs spatial neighbour choice) so they never share numbers.
LANTERN_FUNC uint rng_init(uvec2 pixel, uint frame, uint seed, uint pass) {
  uint h = pcg_hash(pixel.x ^ pcg_hash(pixel.y));
  h = pcg_hash(h ^ frame);
  h = pcg_hash(h ^ seed);
  return pcg_hash(h ^ (pass * 0x9e3779b9u));
}

// Next 32 random bits; advances the LCG state.
LANTERN_FUNC uint rng_next_uint(LANTERN_INOUT(uint) state) {
  uint old_state = state;
  state = state * 747796405u + 2891336453u;
  uint word = ((old_state >> ((old_state >> 28u) + 4u)) ^ old_state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Uniform float in [0, 1): the top 24 bits fill the mantissa exactly, so 1.0 is never returned.
LANTERN_FUNC float rng_next_float(LANTERN_INOUT(uint) state) {
  return float(rng_next_uint(state) >> 8u) * (1.0f / 16777216.0f);
}

LANTERN_FUNC vec2 rng_next_vec2(LANTERN_INOUT(uint) state) {
  float x = rng_next_float(state);
  float y = rng_next_float(state);
  return vec2(x, y);
}

LANTERN_END_SHARED

#endif
