// volume.camera: the media's transmittance along every pixel's camera ray, applied in place to
// the integrator's radiance (one pass for every integrator: baseline, reference and ReSTIR see
// the same attenuation). The ray runs from the camera to the G-buffer's surface point, or for a
// sky pixel along the pixel's view direction to kDirectionalShadowRadii scene radii (the sky is
// seen through the fog too). Residual ratio tracking (lib/volumes.glsl): unbiased, exact in
// homogeneous cells, from its own random stream, so E[radiance x T] = E[radiance] E[T].
// In-scattered light is not added here (single scattering is the next step).
// Reads: radiance, gbuffer position, the scene's volumes. Writes: radiance (in place).
// History: none. Dispatch: one thread per pixel, 8x8 groups; FrameRenderer adds the pass only
// for levels with volumes.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lib/scene_buffers.glsl"
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
  vec3 t = gbuffer_is_sky(position.w)
               ? scene_transmittance(camera, env_camera_ray_dir(fc, pixel),
                                     kDirectionalShadowRadii * fc.scene.x, rng)
               : scene_transmittance_between(camera, position.xyz, rng);
  uint index = pixel.y * push.width + pixel.x;
  vec4 value = radiance.pixels[index];
  vec3 rgb = value.rgb * t;
  if (!(is_finite(rgb.x) && is_finite(rgb.y) && is_finite(rgb.z))) rgb = vec3(0.0);
  radiance.pixels[index] = vec4(max(rgb, vec3(0.0)), value.a);
}
