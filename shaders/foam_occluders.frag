#version 450 core
// What foam pass 6's SSAO samples read at a pixel, packed into one texel so that a sample costs one fetch
// instead of four (foam_occlusion.frag): the foam's opacity (its intensity), the foam's eye depth where it has
// opacity (none where it has not: clear foam occludes nothing), the liquid's and the solids' eye depth.
#include "lib/frame.glsl"

layout(binding = 0) uniform sampler2D foamDepth;  // eye depth, h
layout(binding = 2) uniform sampler2D foamIntensity;
layout(binding = 3) uniform sampler2D fluidEyeDepth;
layout(binding = 4) uniform sampler2D solidEyeDepth;

layout(location = 0) out vec4 outOccluders;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float opacity = texelFetch(foamIntensity, pixel, 0).r;
  outOccluders = vec4(opacity, opacity > 0.0 ? texelFetch(foamDepth, pixel, 0).r : kNoSurfaceDepth,
                      texelFetch(fluidEyeDepth, pixel, 0).r, texelFetch(solidEyeDepth, pixel, 0).r);
}
