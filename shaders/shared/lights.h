// The GPU light list: every emitter the lighting module samples, one 64-byte record each.
// Emissive triangles, point, spot and directional lights share one array so one alias table
// (over power) picks among all of them; `kind` selects how the record is read.
#ifndef LANTERN_SHARED_LIGHTS_H
#define LANTERN_SHARED_LIGHTS_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

LANTERN_CONST uint kLightTriangle = 0u;     // p0 = v0, p1 = v1 - v0, p2 = v2 - v0; one-sided (front)
LANTERN_CONST uint kLightPoint = 1u;        // p0 = position
LANTERN_CONST uint kLightSpot = 2u;         // p0 = position, p1 = direction, p2.x/y = cos outer/inner
LANTERN_CONST uint kLightDirectional = 3u;  // p1 = direction the light travels
LANTERN_CONST uint kLightKindCount = 4u;

// An index that names no light (a removed light in the previous->current remap).
LANTERN_CONST uint kInvalidLight = 0xffffffffu;

struct GpuLight {
  vec4 p0;        // xyz: position or triangle v0; w: kind (as float bits: use light_kind())
  vec4 p1;        // xyz: edge v1-v0 or direction; w: unused
  vec4 p2;        // xyz: edge v2-v0, or (cos outer, cos inner, 0) for spots; w: point/spot
                  // range (punctual_distance_falloff's; 0 = pure inverse square), else 0
  vec4 radiance;  // rgb: W/(sr m^2) for triangles, W/sr for point/spot, W/m^2 for directional
};
LANTERN_STATIC_SIZE(GpuLight, 64);
// rgba32ui texels per GpuLight where shaders fetch it through a texel view (scene_light(),
// lib/scene_buffers.glsl): p0, p1, p2, radiance in that order.
LANTERN_CONST uint kGpuLightTexels = 4u;

LANTERN_FUNC uint light_kind(GpuLight light) { return floatBitsToUint(light.p0.w); }

LANTERN_END_SHARED

#endif
