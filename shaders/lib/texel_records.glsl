// Records a pass only reads, fetched through an rgba32ui texel view: of a render-graph buffer
// (runtime/graph's kGraphTexelFormat; ShaderPass binds a view wherever the shader declares the
// buffer as a utextureBuffer, and a storage buffer otherwise) or of a scene row with a texel
// name (the lights, lib/scene_buffers.glsl). On lavapipe a texel fetch is
// cheaper than a storage-buffer load (restir.spatial 0.81x, restir.temporal 0.88x the time with
// the surfaces and reservoirs as texels, night_market 320x180), and the reuse passes and the
// denoiser read neighbours' records at every tap. Each record is whole texels, members in
// declaration order (tests/layout: TexelFetchedRecordsAreWholeTexels).
#ifndef LANTERN_LIB_TEXEL_RECORDS_GLSL
#define LANTERN_LIB_TEXEL_RECORDS_GLSL

#extension GL_EXT_samplerless_texture_functions : require

#include "shared/lights.h"
#include "shared/reservoir_pack.h"
#include "shared/restir.h"

vec4 vec4_fetch(utextureBuffer texels, uint index) {
  return uintBitsToFloat(texelFetch(texels, int(index)));
}

// The GpuLight whose kGpuLightTexels texels start at texel `first` (the scene's light list, or
// a PresampledLight's first texels).
GpuLight gpu_light_fetch(utextureBuffer texels, uint first) {
  int base = int(first);
  GpuLight light;
  light.p0 = uintBitsToFloat(texelFetch(texels, base));
  light.p1 = uintBitsToFloat(texelFetch(texels, base + 1));
  light.p2 = uintBitsToFloat(texelFetch(texels, base + 2));
  light.radiance = uintBitsToFloat(texelFetch(texels, base + 3));
  return light;
}

RestirSurface restir_surface_fetch(utextureBuffer texels, uint index) {
  int base = int(kRestirSurfaceTexels * index);
  RestirSurface s;
  s.position_depth = uintBitsToFloat(texelFetch(texels, base));
  s.packed = texelFetch(texels, base + 1);
  s.material = texelFetch(texels, base + 2);
  return s;
}

RestirSimilarityKey restir_similarity_key_fetch(utextureBuffer texels, uint index) {
  uvec4 t = texelFetch(texels, int(index));
  return RestirSimilarityKey(uintBitsToFloat(t.x), t.y, t.z, uintBitsToFloat(t.w));
}

PackedReservoir reservoir_fetch(utextureBuffer texels, uint index) {
  uvec4 t = texelFetch(texels, int(index));
  return PackedReservoir(t.x, t.y, uintBitsToFloat(t.z), t.w);
}

#endif
