#version 450 core
// One direction of Green's separable bilateral filter of eye depth ("Screen Space Fluid Rendering for Games",
// GDC 2010): a Gaussian in pixels, whose width is a world size projected at the centre's depth, times a
// Gaussian in depth difference. Neighbours without a surface are left out, so at a silhouette only the inner
// side is averaged: the pull towards the camera that the liquid paper calls Problem 2.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"

layout(binding = 0) uniform sampler2D sourceEyeDepth;

uniform ivec2 direction;            // (1, 0) or (0, 1)
uniform float spatialSigma;         // world units: liquid.bilateral_spatial_sigma × r
uniform float depthSigma;           // world units: liquid.bilateral_depth_sigma × r
uniform int maximumRadiusInPixels;

layout(location = 0) out float outEyeDepth;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float centreDepth = texelFetch(sourceEyeDepth, pixel, 0).r;
  outEyeDepth = kNoSurfaceDepth;
  if (!hasSurface(centreDepth)) return;
  outEyeDepth = centreDepth;

  float sigmaInPixels = spatialSigma * pixelsPerUnitAtDepth(centreDepth);
  int radius = filterRadiusInPixels(3.0 * spatialSigma, centreDepth, maximumRadiusInPixels);
  if (radius < 1 || !(sigmaInPixels > 0.0)) return;
  float depthSum = centreDepth;
  float weightSum = 1.0;
  for (int offset = -radius; offset <= radius; ++offset) {
    if (offset == 0) continue;
    float depth = layerDepthAt(sourceEyeDepth, pixel + offset * direction);
    if (!hasSurface(depth)) continue;
    float spatial = float(offset) / sigmaInPixels;
    float range = (depth - centreDepth) / depthSigma;
    float weight = exp(-0.5 * (spatial * spatial + range * range));
    depthSum += weight * depth;
    weightSum += weight;
  }
  float filtered = depthSum / weightSum;
  if (hasSurface(filtered)) outEyeDepth = filtered;
}
