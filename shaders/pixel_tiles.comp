#version 450 core
// Marks the 16 × 16 pixel tiles (framedata/PixelTiles.h) that hold a pixel of any of the given layers: a
// surface's eye depth (0 < z < kNoSurfaceDepth / 2), or a positive foam intensity, which passes the same test.
// One invocation per tile, which stops at its first such pixel: without shared memory or barriers, which
// llvmpipe runs as coroutines (a work group per tile and an invocation per pixel took 4-7 ms at 480 × 270).
// The passes after it that change only those pixels (smoothing, normals, refraction; the foam's shadow,
// irradiance and blur) draw only the marked tiles.
layout(local_size_x = 8, local_size_y = 8) in;
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"

layout(binding = 0) uniform sampler2D layerEyeDepths[4];  // or the foam's intensity
layout(binding = 0, r8ui) uniform writeonly uimage2D markedTiles;
layout(std430, binding = 1) buffer TileCounter { uint markedTileCount; };

uniform int layerCount;  // how many of layerEyeDepths are bound

bool anySurface(ivec2 first, ivec2 last) {
  for (int layer = 0; layer < layerCount; ++layer)
    for (int y = first.y; y < last.y; ++y)
      for (int x = first.x; x < last.x; ++x)
        if (hasSurface(texelFetch(layerEyeDepths[layer], ivec2(x, y), 0).r)) return true;
  return false;
}

void main() {
  ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(tile, imageSize(markedTiles)))) return;
  int tileSize = int(frame.pixelTiles.x);
  ivec2 first = tile * tileSize;
  ivec2 last = min(first + tileSize, ivec2(frame.viewportSize.xy));
  bool marked = anySurface(first, last);
  imageStore(markedTiles, tile, uvec4(marked ? 1u : 0u));
  if (marked) atomicAdd(markedTileCount, 1u);
}
