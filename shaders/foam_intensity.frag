#version 450 core
// Foam pass 5 (paper 2.3): intensity iota(rho, rho_mod, rho_exp) of the total thickness. It also marks the
// foam's pixels (depth 0 where iota > 0, 1 elsewhere) for the early depth test of the passes after it
// (passes/LayerCoverage.h).
#include "lib/foam_functions.glsl"

layout(binding = 0) uniform sampler2D thickness;

uniform float intensityMod;
uniform float intensityExp;

layout(location = 0) out float outIntensity;

void main() {
  vec3 byType = texelFetch(thickness, ivec2(gl_FragCoord.xy), 0).rgb;
  outIntensity = foamIntensity(byType.r + byType.g + byType.b, intensityMod, intensityExp);
  gl_FragDepth = outIntensity > 0.0 ? 0.0 : 1.0;
}
