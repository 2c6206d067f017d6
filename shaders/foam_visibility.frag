#version 450 core
// Where foam can still be seen, per tile of the screen: for each tile, the eye depth beyond which a foam
// fragment anywhere in it shows nothing. A fragment behind a solid is discarded by the sprite passes, and one
// deeper under the liquid than the attenuation distance eta_max adds no thickness (f_att = 0), so the depth is
// min(solid, liquid + eta_max) at a pixel, and its largest value over the tile. The tiles are read back, and
// the CPU leaves out a particle whose sphere lies wholly beyond them over the tiles its sprite covers
// (prep/HiddenFoam.cpp).
#include "lib/frame.glsl"

layout(binding = 0) uniform sampler2D solidEyeDepth;
layout(binding = 1) uniform sampler2D fluidEyeDepth;  // 1e10 where there is no liquid

uniform int tileSize;
uniform float attenuationDistance;  // eta_max

layout(location = 0) out vec2 outHiddenBeyond;  // x: behind the solids; y: behind solids or under the liquid

void main() {
  ivec2 first = ivec2(gl_FragCoord.xy) * tileSize;
  ivec2 last = min(first + tileSize, ivec2(frame.viewportSize.xy)) - 1;
  float behindSolids = 0.0, hidden = 0.0;
  for (int y = first.y; y <= last.y; ++y)
    for (int x = first.x; x <= last.x; ++x) {
      float solid = texelFetch(solidEyeDepth, ivec2(x, y), 0).r;
      float fluid = texelFetch(fluidEyeDepth, ivec2(x, y), 0).r;
      // A solid depth that is NaN or not positive hides nothing here (the sprite passes would discard every
      // fragment before a non-positive one, so this only culls less).
      if (!(solid > 0.0)) solid = kNoSurfaceDepth;
      behindSolids = max(behindSolids, solid);
      float underLiquid = fluid > 0.0 && fluid < 0.5 * kNoSurfaceDepth ? fluid + attenuationDistance : kNoSurfaceDepth;
      hidden = max(hidden, min(solid, underLiquid));
    }
  outHiddenBeyond = vec2(behindSolids, hidden);
}
