// Reflection test shader: one binding of each common kind, with names, spec constants, push
// constants and a fixed 8x4 workgroup. Also copies input to output so it is a runnable pipeline.
#version 460

layout(local_size_x = 8, local_size_y = 4) in;
layout(constant_id = 3) const bool kUseScale = true;
layout(constant_id = 7) const float kScale = 2.0;

layout(push_constant) uniform Push {
  mat4 transform;
  uvec4 size;
} pc;

layout(std140, set = 0, binding = 0) uniform FrameConstants {
  vec4 tint;
} frame;
layout(std430, set = 0, binding = 1) readonly buffer Input {
  vec4 texels[];
} source;
layout(std430, set = 0, binding = 2) buffer Reservoirs {
  uvec4 data[];
};
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D radiance;
layout(set = 0, binding = 4) uniform sampler2D history;

void main() {
  const uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= pc.size.x || p.y >= pc.size.y) return;
  const uint i = p.y * pc.size.x + p.x;
  vec4 value = source.texels[i] * frame.tint + textureLod(history, vec2(0.5), 0.0);
  if (kUseScale) value *= kScale;
  imageStore(radiance, ivec2(p), value);
  data[i] = uvec4(i);
}
