#version 450 core
// One direction of Truong and Yuksel's narrow-range filter ("A Narrow-Range Filter for Screen-Space Fluid
// Rendering", i3D 2018), the 1D separable form. A Gaussian over a depth range around the centre depth:
// samples nearer than the range are ignored together with their mirror sample (so a slope is not tipped),
// samples farther than it (the background included) are clamped to just behind the centre, and every sample
// accepted inside the range widens the range on its side, so a smooth slope stays inside it.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"

layout(binding = 0) uniform sampler2D sourceEyeDepth;

uniform ivec2 direction;       // (1, 0) or (0, 1)
uniform float filterRadius;    // world units: liquid.narrow_range_radius × r
uniform float threshold;       // world units: liquid.narrow_range_threshold × r
uniform float clampDistance;   // world units: liquid.narrow_range_clamp × r
uniform int maximumRadiusInPixels;

layout(location = 0) out float outEyeDepth;

// The range of one side of the filter, in eye depth.
struct DepthRange {
  float nearest;
  float farthest;
};

// Classifies one sample against its side's range: returns false when it lies in front of the range (to be
// ignored), clamps it when it lies behind, and otherwise widens the range around it.
bool acceptSample(inout float depth, inout DepthRange range, float clampedDepth) {
  if (depth < range.nearest) return false;
  if (depth > range.farthest) {
    depth = clampedDepth;
  } else {
    range.nearest = min(range.nearest, depth - threshold);
    range.farthest = max(range.farthest, depth + threshold);
  }
  return true;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float centreDepth = texelFetch(sourceEyeDepth, pixel, 0).r;
  outEyeDepth = kNoSurfaceDepth;
  if (!hasSurface(centreDepth)) return;
  outEyeDepth = centreDepth;

  int radius = filterRadiusInPixels(filterRadius, centreDepth, maximumRadiusInPixels);
  if (radius < 1) return;
  float sigma = float(radius) / 3.0;
  float clampedDepth = centreDepth + clampDistance;
  DepthRange forwardRange = DepthRange(centreDepth - threshold, centreDepth + threshold);
  DepthRange backwardRange = forwardRange;
  float depthSum = centreDepth;
  float weightSum = 1.0;
  for (int offset = 1; offset <= radius; ++offset) {
    float forwardDepth = layerDepthAt(sourceEyeDepth, pixel + offset * direction);
    float backwardDepth = layerDepthAt(sourceEyeDepth, pixel - offset * direction);
    float weight = exp(-0.5 * float(offset * offset) / (sigma * sigma));
    bool keep = acceptSample(forwardDepth, forwardRange, clampedDepth);
    keep = acceptSample(backwardDepth, backwardRange, clampedDepth) && keep;
    if (!keep) continue;
    depthSum += weight * (forwardDepth + backwardDepth);
    weightSum += 2.0 * weight;
  }
  float filtered = depthSum / weightSum;
  if (hasSurface(filtered)) outEyeDepth = filtered;
}
