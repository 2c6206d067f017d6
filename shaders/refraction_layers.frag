#version 450 core
// The four depth layers the refraction's marches read at every sample (the splash and aggregate front and back
// eye depths), packed into one texel per pixel, so that a sample fetches once what it fetched from up to four
// textures (refraction.frag's frontDepth and backDepth). It also marks the pixels the refraction shades: depth
// 0 where a path starts (a first surface, or everywhere under water), 1 elsewhere. The refraction's early depth
// test then passes over the rest, which its own early return does not do on llvmpipe (docs/frame-cost.md).
#include "lib/frame.glsl"
layout(binding = 0) uniform sampler2D splashFrontDepth;
layout(binding = 1) uniform sampler2D splashBackDepth;
layout(binding = 2) uniform sampler2D aggregateFrontDepth;
layout(binding = 3) uniform sampler2D aggregateBackDepth;

uniform bool hasSplash;
uniform bool hasAggregate;
uniform bool underLiquid;  // the camera is inside the aggregated body: every pixel starts a path

layout(location = 0) out vec4 outDepths;  // splash front, splash back, aggregate front, aggregate back

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  outDepths = vec4(texelFetch(splashFrontDepth, pixel, 0).r, texelFetch(splashBackDepth, pixel, 0).r,
                   texelFetch(aggregateFrontDepth, pixel, 0).r, texelFetch(aggregateBackDepth, pixel, 0).r);
  float firstDepth = min(hasSplash ? outDepths.x : kNoSurfaceDepth, hasAggregate ? outDepths.z : kNoSurfaceDepth);
  gl_FragDepth = (underLiquid || firstDepth < kNoSurfaceDepth * 0.5) ? 0.0 : 1.0;
}
