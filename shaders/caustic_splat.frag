#version 450 core
// Caustics, step 2: adds a triangle of refracted light to the background points it lands on (those whose depth
// matches the triangle's), weighted like the light's shadow (liquid_shadow.frag).
#include "lib/frame.glsl"
#include "lib/optics.glsl"
#include "lib/light_view.glsl"
#include "lib/caustic_receiver.glsl"

layout(binding = 3) uniform sampler2D backgroundEyeDepth;
// 1 in each pixel tile (framedata/PixelTiles.h) a splat lands in, so the lit tiles (lit_tiles.comp) need not
// read every pixel's caustics: reading them took llvmpipe 4-10 ms on a far camera's frame.
layout(binding = 3, r8ui) uniform writeonly uimage2D causticTiles;

in vec3 gCarried;
in float gEyeDepth;
flat in float gConcentration;

layout(location = 0) out vec4 outCaustic;

void main() {
  float eyeDepth = texelFetch(backgroundEyeDepth, ivec2(gl_FragCoord.xy), 0).r;
  if (eyeDepth >= kNoSurfaceDepth * 0.5 || abs(gEyeDepth - eyeDepth) > causticDepthTolerance(eyeDepth)) discard;
  vec3 world = worldPositionFromFragCoord(gl_FragCoord.xy, eyeDepth);
  outCaustic = vec4(lightWeightAt(world) * gCarried * gConcentration, 0.0);
  imageStore(causticTiles, ivec2(gl_FragCoord.xy) / int(frame.pixelTiles.x), uvec4(1u));
}
