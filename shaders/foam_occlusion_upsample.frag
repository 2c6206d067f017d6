#version 450 core
// Foam pass 6 at a reduced resolution (foam.occlusion_block > 1): each foam pixel takes the shadow zeta and
// irradiance I of the four nearest block estimates (foam_occlusion.frag), weighted bilinearly and by how far
// each estimate's depth lies from the pixel's, in units of the pixel's search radius h: foam in front of other
// foam does not lend it its light, nor a spray droplet the shadow of the surface foam behind it. The block
// the pixel lies in always has an estimate (one of its foam pixels has a depth), so every foam pixel gets one.
#include "lib/frame.glsl"

layout(binding = 0) uniform sampler2D blockShadow;      // zeta, estimate's eye depth
layout(binding = 1) uniform sampler2D blockIrradiance;  // I
layout(binding = 2) uniform sampler2D foamDepth;        // eye depth, h
layout(binding = 3) uniform sampler2D foamIntensity;

uniform int blockSize;

layout(location = 0) out vec2 outShadow;  // zeta, and this pixel's eye depth (as foam_occlusion.frag's)
layout(location = 1) out vec4 outIrradiance;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  outShadow = vec2(0.0, kNoSurfaceDepth);
  outIrradiance = vec4(0.0);
  if (texelFetch(foamIntensity, pixel, 0).r <= 0.0) return;
  vec2 depthAndSearchRadius = texelFetch(foamDepth, pixel, 0).rg;
  float depth = depthAndSearchRadius.x;
  if (depth >= kNoSurfaceDepth * 0.5) return;
  // h is relative to half the screen's height (foam_occlusion.frag): in world units at this depth.
  float worldSearchRadius = max(depthAndSearchRadius.y * frame.tanHalfFov.y * depth, 1e-6 * depth);
  // Estimate (i, j) stands at the centre of block (i, j): pixel (blockSize (i + 1/2), blockSize (j + 1/2)).
  vec2 position = (vec2(pixel) + 0.5) / float(blockSize) - 0.5;
  ivec2 base = ivec2(floor(position));
  vec2 blend = position - vec2(base);
  ivec2 last = textureSize(blockShadow, 0) - 1;
  float shadow = 0.0, weightSum = 0.0;
  vec3 irradiance = vec3(0.0);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      ivec2 index = clamp(base + ivec2(i, j), ivec2(0), last);
      vec2 estimate = texelFetch(blockShadow, index, 0).rg;
      if (estimate.y >= kNoSurfaceDepth * 0.5) continue;  // a block without foam
      float bilinear = (i == 0 ? 1.0 - blend.x : blend.x) * (j == 0 ? 1.0 - blend.y : blend.y);
      float apart = (estimate.y - depth) / worldSearchRadius;
      float weight = (bilinear + 1e-3) / (1.0 + apart * apart * apart * apart);
      shadow += weight * estimate.x;
      irradiance += weight * texelFetch(blockIrradiance, index, 0).rgb;
      weightSum += weight;
    }
  if (!(weightSum > 0.0)) return;
  outShadow = vec2(shadow / weightSum, depth);
  outIrradiance = vec4(irradiance / weightSum, 1.0);
}
