#version 450 core
// The liquid's shadow on the background from one light (or, in sky mode, how much sky light a submerged point
// keeps). Each background point, rebuilt from the background's depth, is looked up in the light's view of the
// liquid: a point behind the liquid's front surface is in its shadow. With caustics on, the light that goes
// through the liquid is splatted by the caustic pass and the shadow is the light that does not meet the
// liquid (0 behind it); without, the shadow keeps the light that crosses the liquid straight, with Fresnel at
// both surfaces and Beer-Lambert over the path. Four texels are blended bilinearly, so the edge is soft over
// one texel. Output, added up over the lights: (weight x shadow, weight), and the diffuse direct light the
// light gives the point without the liquid (in the units of Cycles' DiffDir pass), so the lit background can
// tell the lamps' share of the direct light from the sky's.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"
#include "lib/optics.glsl"
#include "lib/light_view.glsl"
#include "lib/background_normal.glsl"

layout(binding = 0) uniform sampler2D backgroundEyeDepth;
layout(binding = 1) uniform sampler2D lightFrontDepth;
layout(binding = 2) uniform sampler2D lightBackDepth;
layout(binding = 3) uniform sampler2D lightFrontNormal;
layout(binding = 4) uniform sampler2D skyOcclusion;  // sky mode: sky_occlusion.frag's samples

uniform int skyOcclusionScale;   // sky mode: pixels per sample of skyOcclusion along each axis; 0: none

// Compiled in three variants (LiquidShadowPass), not switched by uniforms: llvmpipe runs both sides of a branch
// with masks, so each mode would pay for the others' work (measured: the light's shadow 9.2 against 3.8 ms,
// the sky's 9.4 against 6.7, at 480x270; docs/frame-cost.md).
#ifdef SKY_MODE
const bool skyMode = true;            // write the sky light a point keeps instead of a light's shadow
#else
const bool skyMode = false;
#endif
#ifdef TRANSMIT_STRAIGHT
const bool transmitStraight = true;   // no caustic pass: the shadow keeps the light that crosses the liquid
#else
const bool transmitStraight = false;
#endif
uniform float indexOfRefraction;
uniform vec3 absorptionPerUnitLength;
uniform float submergedTolerance;  // sky mode: how far below the liquid's drawn bottom a point still lies in it

layout(location = 0) out vec4 outShadow;
layout(location = 1) out vec4 outLampDiffuse;  // light mode: irradiance x cos / pi x colour, added up

const float kHemisphericalFresnel = 0.066;  // water's Fresnel reflectance averaged over a cosine-weighted sky
const float kDiffusePathFactor = 1.194;     // mean 1 / cos of cosine-weighted sky light refracted into water

// What reaches a point from the light through one light texel's column of liquid.
vec3 shadowThroughTexel(ivec2 texel, vec3 world, float pointDepth) {
  float front = texelFetch(lightFrontDepth, texel, 0).r;
  float texelSize = 2.0 * lightView.tanHalfFov.y * front * lightView.viewportSize.w;
  if (front >= kNoSurfaceDepth * 0.5 || pointDepth <= front + 2.0 * texelSize) return vec3(1.0);
  float back = texelFetch(lightBackDepth, texel, 0).r;
  // The path ends at the liquid's back surface, or at the point itself when the point is submerged.
  float end = min(back, pointDepth);
  float pathLength = abs(end - front) * lightRayLengthPerDepth(vec2(texel) + 0.5);
  if (skyMode) {
    // Sky light enters the surface above and travels down to the point; light past the liquid's bottom is
    // unaffected (that point is under the liquid but not in it).
    // The drawn bottom undulates by about a particle radius; a floor the liquid rests on lies within that.
    if (pointDepth > back + max(2.0 * texelSize, submergedTolerance)) return vec3(1.0);
    return (1.0 - kHemisphericalFresnel) * exp(-absorptionPerUnitLength * pathLength * kDiffusePathFactor);
  }
  if (!transmitStraight) return vec3(0.0);
  vec4 normal = texelFetch(lightFrontNormal, texel, 0);
  vec3 travel = lightTravelAt(world);
  float cosine = normal.w > 0.0 ? abs(dot(normalize(normal.xyz), travel)) : 1.0;
  float fresnel = schlickFresnel(cosine, indexOfRefraction);
  // Leaving through the back surface costs about as much again; a submerged point sees one surface only.
  float exits = pointDepth > back ? 1.0 - fresnel : 1.0;
  return (1.0 - fresnel) * exits * exp(-absorptionPerUnitLength * pathLength);
}

// Sky mode: the sky light a point keeps past liquid other than the body it lies in (sky_occlusion.frag), from
// the four nearest samples, each weighted bilinearly and by how far it lies off the point's tangent plane, in
// pixel widths at the point's depth: a solid's edge does not blend the floor behind it with the solid in
// front, nor a crease the two faces that meet there.
vec3 keptPastOtherLiquid(ivec2 pixel, float eyeDepth) {
  if (skyOcclusionScale == 0) return vec3(1.0);
  // In camera space: the distances are the world's.
  vec3 point = cameraPositionAtPixel(pixel, eyeDepth);
  vec3 normal = backgroundCameraNormal(backgroundEyeDepth, pixel, eyeDepth);
  float pixelWidth = 2.0 * frame.tanHalfFov.y * eyeDepth * frame.viewportSize.w;
  // Sample (i, j) lies at the centre of pixel (scale i + scale / 2, scale j + scale / 2).
  vec2 position = vec2(pixel - skyOcclusionScale / 2) / float(skyOcclusionScale);
  ivec2 base = ivec2(floor(position));
  vec2 blend = position - vec2(base);
  ivec2 last = textureSize(skyOcclusion, 0) - 1;
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      ivec2 index = clamp(base + ivec2(i, j), ivec2(0), last);
      vec4 sample_ = texelFetch(skyOcclusion, index, 0);
      if (!hasSurface(sample_.a)) continue;
      vec2 samplePixel = vec2(min(index * skyOcclusionScale + skyOcclusionScale / 2, ivec2(frame.viewportSize.xy) - 1));
      vec3 offset = cameraRayFromFragCoord(samplePixel + 0.5) * sample_.a - point;
      // Without a normal (a lone pixel), the distance itself.
      float offPlane = (dot(normal, normal) > 0.0 ? abs(dot(offset, normal)) : length(offset)) / pixelWidth;
      float bilinear = (i == 0 ? 1.0 - blend.x : blend.x) * (j == 0 ? 1.0 - blend.y : blend.y);
      float weight = (bilinear + 1e-3) / (1.0 + offPlane * offPlane * offPlane * offPlane);
      sum += weight * sample_.rgb;
      weightSum += weight;
    }
  return weightSum > 0.0 ? sum / weightSum : vec3(1.0);  // only samples of the sky around a lone point
}

void main() {
  float eyeDepth = texelFetch(backgroundEyeDepth, ivec2(gl_FragCoord.xy), 0).r;
  outShadow = skyMode ? vec4(1.0) : vec4(0.0);
  outLampDiffuse = vec4(0.0);
  if (eyeDepth >= kNoSurfaceDepth * 0.5) return;  // Nothing there to shadow.
  vec3 world = worldPositionFromFragCoord(gl_FragCoord.xy, eyeDepth);
  float weight = skyMode ? 1.0 : lightWeightAt(world);
  if (!skyMode) {
    float cosine = max(dot(backgroundNormal(backgroundEyeDepth, ivec2(gl_FragCoord.xy), eyeDepth), -lightTravelAt(world)), 0.0);
    outLampDiffuse = vec4(lightIrradianceAt(world) * cosine / 3.14159265358979 * lightColor, 0.0);
  }
  vec2 texel = lightTexelFromWorld(world);
  vec3 shadow = vec3(1.0);
  if (insideLightView(texel) && lightEyeDepthOf(world) > 0.0) {
    vec2 footprint = clamp(texel - 0.5, vec2(0.0), lightView.viewportSize.xy - 1.001);
    ivec2 base = ivec2(floor(footprint));
    vec2 blend = footprint - vec2(base);
    float pointDepth = lightEyeDepthOf(world);
    vec3 s00 = shadowThroughTexel(base, world, pointDepth), s10 = shadowThroughTexel(base + ivec2(1, 0), world, pointDepth);
    vec3 s01 = shadowThroughTexel(base + ivec2(0, 1), world, pointDepth), s11 = shadowThroughTexel(base + ivec2(1, 1), world, pointDepth);
    shadow = mix(mix(s00, s10, blend.x), mix(s01, s11, blend.x), blend.y);
  }
  if (skyMode) shadow *= keptPastOtherLiquid(ivec2(gl_FragCoord.xy), eyeDepth);
  outShadow = skyMode ? vec4(shadow, 1.0) : vec4(weight * shadow, weight);
}
