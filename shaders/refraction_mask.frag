#version 450 core
// The refraction pass's pixel mask: depth 0 where the first surface is liquid (a splash's or the aggregated
// body's front layer), left at the cleared 1 elsewhere. The refraction pass then tests depth before its
// fragment shader (early_fragment_tests), so llvmpipe skips its background blocks instead of running the
// whole shader with every lane masked off (docs/frame-cost.md).
#include "lib/frame.glsl"

layout(binding = 0) uniform sampler2D splashFrontDepth;
layout(binding = 2) uniform sampler2D aggregateFrontDepth;

uniform bool hasSplash;
uniform bool hasAggregate;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float splashDepth = hasSplash ? texelFetch(splashFrontDepth, pixel, 0).r : kNoSurfaceDepth;
  float aggregateDepth = hasAggregate ? texelFetch(aggregateFrontDepth, pixel, 0).r : kNoSurfaceDepth;
  // The same test as refraction.frag's for a pixel with no liquid.
  if (min(splashDepth, aggregateDepth) >= kNoSurfaceDepth * 0.5) discard;
  gl_FragDepth = 0.0;
}
