// The small bridge that lets a header in shaders/shared/ compile as both GLSL and C++.
// Rules for shared headers (std430 layout, see STYLE.md): 4-byte scalars, vec4/uvec4/mat4 members
// only (no vec3, no bool), named padding, and a LANTERN_STATIC_SIZE check after each struct.
// Functions use GLSL spelling; in C++ the GLSL built-ins come from GLM.
// C++ leaves the order of argument evaluation unspecified (GLSL: left to right): never draw
// two random numbers (rng_next_*) or make other side effects inside one call's arguments.
#ifndef LANTERN_SHARED_LANG_H
#define LANTERN_SHARED_LANG_H

#ifdef __cplusplus
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>

#define LANTERN_BEGIN_SHARED namespace lantern::gpu {
#define LANTERN_END_SHARED }
// Compile-time constant usable in both languages: LANTERN_CONST uint kFoo = 4u;
#define LANTERN_CONST inline constexpr
#define LANTERN_INOUT(T) T&
#define LANTERN_OUT(T) T&
#define LANTERN_STATIC_SIZE(T, bytes) static_assert(sizeof(T) == (bytes), #T " size must match GLSL std430")
#define LANTERN_FUNC inline

namespace lantern::gpu {
using uint = std::uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using uvec3 = glm::uvec3;
using uvec4 = glm::uvec4;
using ivec2 = glm::ivec2;
using ivec4 = glm::ivec4;
using mat3 = glm::mat3;
using mat4 = glm::mat4;
using glm::abs;
using glm::acos;
using glm::atan;
using glm::clamp;
using glm::cos;
using glm::cross;
using glm::dot;
using glm::exp;
using glm::exp2;
using glm::floatBitsToUint;
using glm::floor;
using glm::fract;
using glm::inversesqrt;
using glm::length;
using glm::log;
using glm::log2;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::packHalf2x16;
using glm::packSnorm2x16;
using glm::packUnorm2x16;
using glm::packUnorm4x8;
using glm::pow;
using glm::reflect;
using glm::sin;
using glm::sqrt;
using glm::tan;
using glm::uintBitsToFloat;
using glm::unpackHalf2x16;
using glm::unpackSnorm2x16;
using glm::unpackUnorm2x16;
using glm::unpackUnorm4x8;
using std::pow;
inline bool isnan(float x) { return x != x; }
inline bool isinf(float x) { return x == x && (x - x) != 0.0f; }
}  // namespace lantern::gpu

#else  // GLSL

#define LANTERN_BEGIN_SHARED
#define LANTERN_END_SHARED
#define LANTERN_CONST const
#define LANTERN_INOUT(T) inout T
#define LANTERN_OUT(T) out T
#define LANTERN_STATIC_SIZE(T, bytes)
#define LANTERN_FUNC

#endif

#endif  // LANTERN_SHARED_LANG_H
