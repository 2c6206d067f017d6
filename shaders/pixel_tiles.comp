#version 450 core
// Marks the 16 × 16 pixel tiles (framedata/PixelTiles.h) that hold a pixel of any of the given layers: a
// surface's eye depth (0 < z < kNoSurfaceDepth / 2), or a positive foam intensity, which passes the same test.
// One work group per tile, one invocation per pixel. The passes after it that change only those pixels
// (smoothing, normals, refraction; the foam's shadow, irradiance and blur) draw only the marked tiles.
layout(local_size_x = 16, local_size_y = 16) in;
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"

layout(binding = 0) uniform sampler2D layerEyeDepths[4];  // or the foam's intensity
layout(binding = 0, r8ui) uniform writeonly uimage2D markedTiles;
layout(std430, binding = 1) buffer TileCounter { uint markedTileCount; };

uniform int layerCount;  // how many of layerEyeDepths are bound

shared bool anySurface;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (gl_LocalInvocationIndex == 0u) anySurface = false;
  barrier();
  if (all(lessThan(pixel, ivec2(frame.viewportSize.xy))))
    for (int layer = 0; layer < layerCount; ++layer)
      if (hasSurface(texelFetch(layerEyeDepths[layer], pixel, 0).r)) anySurface = true;
  barrier();
  if (gl_LocalInvocationIndex != 0u) return;
  imageStore(markedTiles, ivec2(gl_WorkGroupID.xy), uvec4(anySurface ? 1u : 0u));
  if (anySurface) atomicAdd(markedTileCount, 1u);
}
