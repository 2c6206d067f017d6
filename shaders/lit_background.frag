#version 450 core
// The background lit as the liquid lets it be: every light's shadow and caustics (the sums of
// liquid_shadow.frag and caustic_splat.frag, weighted by each light's irradiance) scale the lamps' direct
// light, and the sky light a point keeps scales the rest. With Cycles' light passes: Combined - direct
// (s (1 - shadow - caustics) + (1 - s)(1 - sky)) - indirect (1 - sky), where "direct" is Cycles' direct diffuse
// and glossy light and s the lamps' share of it. Cycles counts the world's light as direct too (the sky is
// sampled like a lamp), so s is the lamps' diffuse light at the point without the liquid (liquid_shadow.frag)
// over DiffDir, at most 1; the glossy light takes the diffuse share (caustics add diffuse light only). Without
// the passes, `directFraction` of the background is taken as the lamps'.
//
// The sky light a point keeps is upsampled from the sky occlusion's samples, which hold what a point keeps
// below the liquid's surface and past other liquid (sky_occlusion.frag). Where that pass does not run
// (light.sky_occlusion_directions 0), what a point keeps below the surface is found here, at every pixel,
// from the sky's view. With the samples and one light whose caustics are on, the pass also finds that light's
// shadow itself (SHADOW_IN_PLACE, lib/liquid_shadow.glsl) instead of reading the shadow pass's sums: one
// full-screen pass, two targets and one rebuilt normal fewer. These are variants compiled from this source
// (chosen by LitBackgroundPass), not switched by a uniform: llvmpipe runs both sides of a branch with masks.
// The PLAIN variant writes the colour of the tiles where no light changes the background (lit_tiles.comp), whose
// other targets LitBackgroundPass clears to what the full variant writes there.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"
#include "lib/optics.glsl"
#include "lib/light_view.glsl"
#include "lib/background_normal.glsl"

layout(binding = 0) uniform sampler2D backgroundColor;
layout(binding = 1) uniform sampler2D shadowSum;    // (sum of weight x shadow, sum of weight)
layout(binding = 2) uniform sampler2D causticSum;   // sum of weight x caustic
layout(binding = 3) uniform sampler2D backgroundEyeDepth;
layout(binding = 4) uniform sampler2D directDiffuse;  // DiffCol x DiffDir; alpha: DiffDir
layout(binding = 5) uniform sampler2D directGlossy;   // GlossCol x GlossDir
layout(binding = 6) uniform sampler2D indirectLight;  // DiffCol x DiffInd + GlossCol x GlossInd
layout(binding = 7) uniform sampler2D lampDiffuse;    // the lamps' diffuse light without the liquid

// The view bound at binding 2 as lightView: the one light's with SHADOW_IN_PLACE, the sky's without the sky
// occlusion's samples, none in the other variant.
layout(binding = 8) uniform sampler2D lightFrontDepth;
layout(binding = 9) uniform sampler2D lightBackDepth;

#include "lib/light_column.glsl"

#ifdef SHADOW_IN_PLACE
layout(binding = 11) uniform sampler2D lightFrontNormal;

#include "lib/liquid_shadow.glsl"
#endif

uniform bool hasLightPasses;
uniform float directFraction;
// No lamp sees the liquid and the world's light alone lights the background (light.sky_without_lamps): the
// liquid's shadow is then the world's, the sky light kept, so that liquid_shadow stays the multiplier of the
// background's light a compositor applies, whatever share of it it takes as the lamps'.
uniform bool worldAlone;

layout(location = 0) out vec4 outColor;
#ifndef PLAIN
layout(location = 1) out vec4 outShadow;
layout(location = 2) out vec4 outCaustics;
layout(location = 3) out vec4 outSky;
#endif

#ifdef SKY_OCCLUSION_SAMPLES
layout(binding = 10) uniform sampler2D skyOcclusion;  // sky_occlusion.frag's samples
uniform int skyOcclusionScale;                        // pixels per sample along each axis

// The sky light a point keeps, from the four nearest samples, each weighted bilinearly and by how far it lies
// off the point's tangent plane, in pixel widths at the point's depth: a solid's edge does not blend the floor
// behind it with the solid in front, nor a crease the two faces that meet there. A point whose four samples
// all lack a surface (a lone pixel against the sky) keeps all of it.
// `normal`: the point's in camera space (backgroundCameraNormal).
vec3 skyKeptAt(ivec2 pixel, float eyeDepth, vec3 normal) {
  if (!hasSurface(eyeDepth)) return vec3(1.0);  // Nothing there to lose it.
  // In camera space: the distances are the world's.
  vec3 point = cameraPositionAtPixel(pixel, eyeDepth);
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
  return weightSum > 0.0 ? sum / weightSum : vec3(1.0);
}
#else
uniform vec3 absorptionPerUnitLength;
uniform float submergedTolerance;  // how far below the liquid's drawn bottom a point still lies in it

#include "lib/submerged_sky.glsl"

// The sky and bounced light a point keeps below the liquid's surface.
vec3 skyKeptAt(float eyeDepth) {
  if (!hasSurface(eyeDepth)) return vec3(1.0);  // Nothing there to lose it.
  return submergedSkyKept(worldPositionFromFragCoord(gl_FragCoord.xy, eyeDepth));
}
#endif

// The background lit as the lights leave it: with Cycles' light passes exactly, else with directFraction.
vec3 litColour(ivec2 pixel, vec3 background, vec3 shadow, vec3 caustics, vec3 sky, vec3 lampLight) {
  if (hasLightPasses) {
    vec4 diffuse = texelFetch(directDiffuse, pixel, 0);
    float lamps = dot(lampLight, vec3(1.0 / 3.0));
    float share = diffuse.a > 0.0 ? clamp(lamps / diffuse.a, 0.0, 1.0) : 1.0;
    vec3 skyLost = (1.0 - share) * (1.0 - sky);
    vec3 colour = background - diffuse.rgb * (share * (1.0 - shadow - caustics) + skyLost) -
                  texelFetch(directGlossy, pixel, 0).rgb * (share * (1.0 - shadow) + skyLost) -
                  texelFetch(indirectLight, pixel, 0).rgb * (1.0 - sky);
    return max(colour, vec3(0.0));
  }
  // background (f (shadow + caustics) + (1 - f) sky), written as what the liquid takes from the background,
  // so that where it takes nothing the result is the background to the bit whatever f is (as PLAIN writes it).
  return background - background * (directFraction * (1.0 - shadow - caustics) + (1.0 - directFraction) * (1.0 - sky));
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 background = texelFetch(backgroundColor, pixel, 0);
#ifdef PLAIN
  // A tile where no light changes the background (lit_tiles.comp): what litColour gives there, with all of the
  // lamps' and the sky's light kept and no caustics. Every term it takes away is then a finite value times
  // zero, so the background comes out to the bit (clamped at zero, as litColour clamps it, with the passes).
  outColor = vec4(hasLightPasses ? max(background.rgb, vec3(0.0)) : background.rgb, background.a);
#else
  float eyeDepth = texelFetch(backgroundEyeDepth, pixel, 0).r;
#ifdef SKY_OCCLUSION_SAMPLES
  vec3 cameraNormal = hasSurface(eyeDepth) ? backgroundCameraNormal(backgroundEyeDepth, pixel, eyeDepth) : vec3(0.0);
  vec3 sky = skyKeptAt(pixel, eyeDepth, cameraNormal);
#else
  vec3 sky = skyKeptAt(eyeDepth);
#endif
#ifdef SHADOW_IN_PLACE
  // What the shadow pass would have added up for its one light (liquid_shadow.frag).
  vec4 shadowWeighted = vec4(0.0);
  vec3 lampLight = vec3(0.0);
  if (hasSurface(eyeDepth)) {
    vec3 world = worldPositionFromFragCoord(gl_FragCoord.xy, eyeDepth);
    float weight = lightWeightAt(world);
    shadowWeighted = vec4(weight * liquidShadowAt(world), weight);
    lampLight = lampDiffuseAt(world, mat3(frame.worldFromCamera) * cameraNormal);
  }
#else
  vec4 shadowWeighted = texelFetch(shadowSum, pixel, 0);
  vec3 lampLight = texelFetch(lampDiffuse, pixel, 0).rgb;
#endif
  bool lit = shadowWeighted.a > 0.0;
  vec3 shadow = lit ? shadowWeighted.rgb / shadowWeighted.a : vec3(1.0);
  vec3 caustics = lit ? texelFetch(causticSum, pixel, 0).rgb / shadowWeighted.a : vec3(0.0);
  outColor = vec4(litColour(pixel, background.rgb, shadow, caustics, sky, lampLight), background.a);
  outShadow = vec4(worldAlone ? sky : shadow, 1.0);
  outCaustics = vec4(caustics, 1.0);
  outSky = vec4(sky, 1.0);
#endif
}
