#version 450 core
// D_all of the adaptive ray marching paper (4.2): the nearest front surface of all particles, splashes and
// aggregates, where each ray enters; and that surface's normal, which the screen-space normal pass falls back
// on where the smoothed depth has no neighbour.
layout(local_size_x = 8, local_size_y = 8) in;
#include "lib/frame.glsl"

layout(binding = 0) uniform sampler2D splashFrontDepth;
layout(binding = 1) uniform sampler2D splashFrontNormal;
layout(binding = 2) uniform sampler2D aggregateFrontDepth;
layout(binding = 3) uniform sampler2D aggregateFrontNormal;
layout(binding = 0, r32f) uniform writeonly image2D allDepth;
layout(binding = 1, rgba16f) uniform writeonly image2D allNormal;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.viewportSize.xy)))) return;
  float splash = texelFetch(splashFrontDepth, pixel, 0).r;
  float aggregate = texelFetch(aggregateFrontDepth, pixel, 0).r;
  bool splashFirst = splash < aggregate;
  imageStore(allDepth, pixel, vec4(min(splash, aggregate)));
  imageStore(allNormal, pixel, splashFirst ? texelFetch(splashFrontNormal, pixel, 0)
                                           : texelFetch(aggregateFrontNormal, pixel, 0));
}
