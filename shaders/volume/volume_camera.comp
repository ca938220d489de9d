// volume.camera: what the media do to every pixel's camera ray, applied to the integrator's
// radiance in place (one pass for every integrator: baseline, reference and ReSTIR see the same
// media): L = T(camera, surface) L_surface + in-scattered light, single scattering from every
// light kind (lib/volume_scatter.glsl). The ray runs from the camera to the G-buffer's surface
// point, or for a sky pixel along the pixel's view direction to kDirectionalShadowRadii scene
// radii (the sky is seen through the fog too). Each of push.samples samples is one
// in-scattering sample per volume (with kVolumePushPhaseMis, the reference's, a light-sampled
// and a phase-sampled one, MIS-weighted) and one transmittance estimate to the surface (residual ratio
// tracking, lib/volumes.glsl: unbiased, exact in homogeneous cells; it continues the first
// volume's walk to its scattering point); their means are used. Its own random stream, so
// E[radiance x T] = E[radiance] E[T].
// Reads: radiance, gbuffer position, the scene (volumes, lights, environment, visibility).
// Writes: radiance (in place). History: none. Dispatch: one thread per pixel, 8x8 groups;
// FrameRenderer adds the pass only for levels with volumes.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lib/scene_buffers.glsl"
#include "lib/volume_scatter.glsl"
#include "shared/gbuffer.h"
#include "shared/light_eval.h"

layout(local_size_x = kVolumeGroupSize, local_size_y = kVolumeGroupSize) in;

layout(std430, binding = PASS_BINDING(0)) restrict buffer Radiance { vec4 pixels[]; } radiance;
layout(binding = PASS_BINDING(1), rgba32f) uniform readonly image2D gbuffer_position;

layout(push_constant) uniform Push { VolumePush push; };

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= push.width || pixel.y >= push.height) return;
  FrameConstants fc = frame_constants.frame;
  vec3 camera = fc.camera_position.xyz;
  vec4 position = imageLoad(gbuffer_position, ivec2(pixel));
  uint rng = frame_rng(pixel, kVolumeRngCamera);
  vec3 dir;
  float t_end;
  media_camera_ray(fc, pixel, position, dir, t_end);
  uint samples = max(push.samples, 1u);
  vec3 t = vec3(0.0);
  vec3 inscattered = vec3(0.0);
  for (uint s = 0u; s < samples; ++s) {
    vec3 t_surface;
    inscattered += scene_inscatter_sample(camera, dir, t_end,
                                          (push.flags & kVolumePushPhaseMis) != 0u, rng, t_surface);
    t += t_surface;
  }
  t /= float(samples);
  inscattered /= float(samples);
  uint index = pixel.y * push.width + pixel.x;
  vec4 value = radiance.pixels[index];
  vec3 rgb = value.rgb * t + inscattered;
  if (!(is_finite(rgb.x) && is_finite(rgb.y) && is_finite(rgb.z))) rgb = vec3(0.0);
  radiance.pixels[index] = vec4(max(rgb, vec3(0.0)), value.a);
}
