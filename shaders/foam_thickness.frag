#version 450 core
// Foam pass 4 (paper 2.2): additive thickness per foam type, each fragment weighted by its type's falloff, the
// lifetime fade, and the attenuation below the liquid surface. Fragments behind solids are discarded.
#include "lib/frame.glsl"
#include "lib/foam_functions.glsl"
#include "lib/foam_sprite.glsl"

layout(binding = 0) uniform sampler2D solidEyeDepth;
layout(binding = 1) uniform sampler2D fluidEyeDepth;

uniform vec3 falloffN;  // exponent n per type: spray, surface foam, bubble
uniform vec3 falloffM;  // exponent m per type
uniform vec2 lifetimeFalloff;     // n, m of f(l, 1, n, m)
uniform vec3 attenuation;         // eta_max, eta_n, eta_m of f_att

layout(location = 0) out vec4 outThickness;  // r spray, g surface foam, b bubble

void main() {
  FoamSpriteFragment fragment;
  if (!foamSpriteFragment(fragment)) discard;
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  if (fragment.eyeDepth >= texelFetch(solidEyeDepth, pixel, 0).r) discard;
  float shape = foamFalloff(fragment.distanceFromCentre, 1.0, falloffN[vFoamType], falloffM[vFoamType]);
  // Bubbles are hollow rings: bright at the rim, clear in the middle.
  float weight = vFoamType == 2 ? 1.0 - shape : shape;
  weight *= foamFalloff(vAge, 1.0, lifetimeFalloff.x, lifetimeFalloff.y);
  float fluidDepth = texelFetch(fluidEyeDepth, pixel, 0).r;
  if (fluidDepth > 0.0 && fluidDepth < fragment.eyeDepth)
    weight *= foamFalloff(fragment.eyeDepth - fluidDepth, attenuation.x, attenuation.y, attenuation.z);
  outThickness = vec4(0.0);
  outThickness[vFoamType] = weight;
}
