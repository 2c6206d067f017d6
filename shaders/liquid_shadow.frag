#version 450 core
// The liquid's shadow on the background from one light. Each background point, rebuilt from the background's
// depth, is looked up in the light's view of the liquid: a point behind the liquid's front surface is in its
// shadow. With caustics on, the light that goes through the liquid is splatted by the caustic pass and the
// shadow is the light that does not meet the liquid (0 behind it); without, the shadow keeps the light that
// crosses the liquid straight, with Fresnel at both surfaces and Beer-Lambert over the path. Four texels are
// blended bilinearly, so the edge is soft over one texel. Output, added up over the lights: (weight x shadow,
// weight), and the diffuse direct light the light gives the point without the liquid (in the units of Cycles'
// DiffDir pass), so the lit background can tell the lamps' share of the direct light from the sky's.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"
#include "lib/optics.glsl"
#include "lib/light_view.glsl"
#include "lib/background_normal.glsl"

layout(binding = 0) uniform sampler2D backgroundEyeDepth;
layout(binding = 1) uniform sampler2D lightFrontDepth;
layout(binding = 2) uniform sampler2D lightBackDepth;
layout(binding = 3) uniform sampler2D lightFrontNormal;

#include "lib/light_column.glsl"

// Compiled in two variants (LiquidShadowPass), not switched by a uniform: llvmpipe runs both sides of a branch
// with masks, so each mode would pay for the other's work (measured: 9.2 against 3.8 ms at 480x270;
// docs/frame-cost.md).
#ifdef TRANSMIT_STRAIGHT
const bool transmitStraight = true;   // no caustic pass: the shadow keeps the light that crosses the liquid
#else
const bool transmitStraight = false;
#endif
uniform float indexOfRefraction;
uniform vec3 absorptionPerUnitLength;

layout(location = 0) out vec4 outShadow;
layout(location = 1) out vec4 outLampDiffuse;  // irradiance x cos / pi x colour, added up

// What reaches a point from the light through one light texel's column of liquid.
vec3 shadowThroughTexel(ivec2 texel, vec3 world, float pointDepth) {
  float front, back, texelSize;
  if (!liquidInColumn(texel, pointDepth, front, back, texelSize)) return vec3(1.0);
  if (!transmitStraight) return vec3(0.0);
  float pathLength = pathInColumn(texel, front, back, pointDepth);
  vec4 normal = texelFetch(lightFrontNormal, texel, 0);
  vec3 travel = lightTravelAt(world);
  float cosine = normal.w > 0.0 ? abs(dot(normalize(normal.xyz), travel)) : 1.0;
  float fresnel = schlickFresnel(cosine, indexOfRefraction);
  // Leaving through the back surface costs about as much again; a submerged point sees one surface only.
  float exits = pointDepth > back ? 1.0 - fresnel : 1.0;
  return (1.0 - fresnel) * exits * exp(-absorptionPerUnitLength * pathLength);
}

void main() {
  float eyeDepth = texelFetch(backgroundEyeDepth, ivec2(gl_FragCoord.xy), 0).r;
  outShadow = vec4(0.0);
  outLampDiffuse = vec4(0.0);
  if (eyeDepth >= kNoSurfaceDepth * 0.5) return;  // Nothing there to shadow.
  vec3 world = worldPositionFromFragCoord(gl_FragCoord.xy, eyeDepth);
  float weight = lightWeightAt(world);
  float cosine = max(dot(backgroundNormal(backgroundEyeDepth, ivec2(gl_FragCoord.xy), eyeDepth), -lightTravelAt(world)), 0.0);
  outLampDiffuse = vec4(lightIrradianceAt(world) * cosine / 3.14159265358979 * lightColor, 0.0);
  vec2 texel = lightTexelFromWorld(world);
  vec3 shadow = vec3(1.0);
  if (insideLightView(texel) && lightEyeDepthOf(world) > 0.0) {
    ivec2 base;
    vec2 blend;
    lightFootprint(texel, base, blend);
    float pointDepth = lightEyeDepthOf(world);
    vec3 s00 = shadowThroughTexel(base, world, pointDepth), s10 = shadowThroughTexel(base + ivec2(1, 0), world, pointDepth);
    vec3 s01 = shadowThroughTexel(base + ivec2(0, 1), world, pointDepth), s11 = shadowThroughTexel(base + ivec2(1, 1), world, pointDepth);
    shadow = mix(mix(s00, s10, blend.x), mix(s01, s11, blend.x), blend.y);
  }
  outShadow = vec4(weight * shadow, weight);
}
