#version 450 core
// Foam pass 5 (paper 2.3): intensity iota(rho, rho_mod, rho_exp) of the total thickness.
#include "lib/foam_functions.glsl"

layout(binding = 0) uniform sampler2D thickness;

uniform float intensityMod;
uniform float intensityExp;

layout(location = 0) out float outIntensity;

void main() {
  vec3 byType = texelFetch(thickness, ivec2(gl_FragCoord.xy), 0).rgb;
  outIntensity = foamIntensity(byType.r + byType.g + byType.b, intensityMod, intensityExp);
}
