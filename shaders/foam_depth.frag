#version 450 core
// Foam pass 3 (paper 2.1): the nearest foam sphere's planar eye depth with the search radius h, and its world
// normal. Fragments behind the solids are dropped: nothing of them can be seen or shade the foam in front.
#include "lib/frame.glsl"
#include "lib/foam_sprite.glsl"

layout(binding = 0) uniform sampler2D solidEyeDepth;

layout(location = 0) out vec2 outDepthAndSearchRadius;  // eye depth (1e10 where none), h
layout(location = 1) out vec4 outNormal;                // world normal, coverage

void main() {
  FoamSpriteFragment fragment;
  if (!foamSpriteFragment(fragment)) discard;
  if (fragment.eyeDepth >= texelFetch(solidEyeDepth, ivec2(gl_FragCoord.xy), 0).r) discard;
  gl_FragDepth = depthBufferFromEyeDepth(fragment.eyeDepth);
  outDepthAndSearchRadius = vec2(fragment.eyeDepth, vSearchRadius);
  // (u, v, w) is a camera-space normal; the camera's rotation takes it to the world.
  outNormal = vec4(mat3(frame.worldFromCamera) * fragment.cameraNormal, 1.0);
}
