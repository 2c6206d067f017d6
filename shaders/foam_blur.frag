#version 450 core
// Foam pass 7 (paper 2.5): a separable Gaussian blur of the shadow zeta and the irradiance I over foam pixels,
// of radius blurRadiusFactor * h_screen (h_screen: the first SSAO pass's search radius in pixels, at the
// pixel being filtered), with sigma = radius / 2. The vertical run (finalRun) then colours the shadow, scales
// the irradiance and writes the foam layers: foam = iota (I_final - zeta_final), alpha iota, and the same split
// by foam type in proportion to each type's share of the thickness.
#include "lib/frame.glsl"

layout(binding = 0) uniform sampler2D shadowInput;
layout(binding = 1) uniform sampler2D irradianceInput;
layout(binding = 2) uniform sampler2D foamDepth;  // eye depth, h
layout(binding = 3) uniform sampler2D foamIntensity;
layout(binding = 4) uniform sampler2D thickness;  // per type

uniform ivec2 direction;
uniform bool finalRun;
uniform float blurRadiusFactor;
uniform float initialRadiusFactor;
uniform vec3 shadowColor;
uniform float irradianceScale;

const int kMaximumBlurRadius = 32;  // pixels: bounds the cost for foam right in front of the camera

layout(location = 0) out float outShadow;       // first run: blurred zeta; final run: unused
layout(location = 1) out vec4 outIrradiance;    // first run: blurred I
layout(location = 2) out vec4 outFoam;          // final run: premultiplied foam
layout(location = 3) out vec4 outSpray;
layout(location = 4) out vec4 outSurface;
layout(location = 5) out vec4 outBubble;
layout(location = 6) out vec4 outShadowFinal;   // zeta_final
layout(location = 7) out vec4 outIrradianceFinal;  // I_final

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  ivec2 size = ivec2(frame.viewportSize.xy);
  float intensity = texelFetch(foamIntensity, pixel, 0).r;
  float shadow = 0.0;
  vec3 irradiance = vec3(0.0);
  if (intensity > 0.0) {
    float screenRadius = texelFetch(foamDepth, pixel, 0).g * initialRadiusFactor * 0.5 * frame.viewportSize.y;
    float radius = min(blurRadiusFactor * screenRadius, float(kMaximumBlurRadius));
    int taps = int(radius);
    float sigma = max(radius * 0.5, 1e-3);
    float weights = 0.0;
    for (int offset = -taps; offset <= taps; ++offset) {
      ivec2 neighbour = pixel + direction * offset;
      if (any(lessThan(neighbour, ivec2(0))) || any(greaterThanEqual(neighbour, size))) continue;
      // Only foam is averaged: pixels without foam have no shadow or irradiance to give.
      if (texelFetch(foamIntensity, neighbour, 0).r <= 0.0) continue;
      float weight = exp(-0.5 * float(offset * offset) / (sigma * sigma));
      shadow += weight * texelFetch(shadowInput, neighbour, 0).r;
      irradiance += weight * texelFetch(irradianceInput, neighbour, 0).rgb;
      weights += weight;
    }
    shadow /= weights;  // the centre pixel is foam, so weights >= 1
    irradiance /= weights;
  }
  outShadow = shadow;
  outIrradiance = vec4(irradiance, 1.0);
  if (!finalRun) return;

  vec3 shadowFinal = clamp(shadow * (vec3(1.0) - shadowColor), 0.0, 1.0);
  vec3 irradianceFinal = clamp(irradianceScale * irradiance, 0.0, 1.0);
  // The paper's C = (1 - iota) C_bg + iota (I_final - zeta_final); a shadow deeper than the light would make
  // negative colour, so the difference stops at black.
  vec3 colour = max(irradianceFinal - shadowFinal, 0.0);
  outFoam = intensity * vec4(colour, 1.0);
  vec3 byType = texelFetch(thickness, pixel, 0).rgb;
  float total = byType.r + byType.g + byType.b;
  vec3 share = total > 0.0 ? byType / total : vec3(0.0);
  outSpray = share.r * outFoam;
  outSurface = share.g * outFoam;
  outBubble = share.b * outFoam;
  outShadowFinal = vec4(shadowFinal, 1.0);
  outIrradianceFinal = vec4(irradianceFinal, 1.0);
}
