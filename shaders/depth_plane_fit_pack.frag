#version 450 core
// Packs a depth layer for the plane fit's rounds (depth_plane_fit.frag): each pixel's original world normal
// in xyz and its eye depth in w, so that a round reads one texel a tap instead of two. An empty pixel (NaN
// and non-positive depths included) is written as the rounds write one: no normal, kNoSurfaceDepth.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"

layout(binding = 0) uniform sampler2D eyeDepth;
layout(binding = 1) uniform sampler2D originalNormal;

layout(location = 0) out vec4 outSurface;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(eyeDepth, pixel, 0).r;
  outSurface = hasSurface(depth) ? vec4(texelFetch(originalNormal, pixel, 0).xyz, depth)
                                 : vec4(0.0, 0.0, 0.0, kNoSurfaceDepth);
}
