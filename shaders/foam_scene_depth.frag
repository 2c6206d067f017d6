#version 450 core
// Foam passes 1 and 2: the liquid's planar eye depth, from the liquid pipeline's first surface, from the
// depth pass of a render that includes the liquid, or the nearer of both. A liquid depth that lies on the
// solids (within a thousandth, the noise of two renders' depth passes) is no liquid. The solids' depth is the
// background's (BackgroundPass).
#include "lib/frame.glsl"

layout(binding = 0) uniform sampler2D solidEyeDepth;
layout(binding = 1) uniform sampler2D liquidFrontDepth;
layout(binding = 2) uniform sampler2D renderedLiquidDepth;

uniform bool hasLiquidFront;
uniform bool hasRenderedLiquid;

layout(location = 0) out float outFluidEyeDepth;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float fluid = kNoSurfaceDepth;
  if (hasLiquidFront) fluid = min(fluid, texelFetch(liquidFrontDepth, pixel, 0).r);
  if (hasRenderedLiquid) {
    float rendered = texelFetch(renderedLiquidDepth, pixel, 0).r;
    if (!isnan(rendered) && rendered > 0.0) fluid = min(fluid, rendered);
  }
  float solid = texelFetch(solidEyeDepth, pixel, 0).r;
  outFluidEyeDepth = fluid < solid * 0.999 ? fluid : kNoSurfaceDepth;
}
