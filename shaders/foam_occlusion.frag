#version 450 core
// Foam pass 6 (paper 2.4): the shadow zeta from multi-pass screen-space ambient occlusion with Halton samples,
// and the irradiance I from the environment and the scene's lights, per foam pixel, or per block of
// foam.occlusion_block pixels a side, estimated at one of its foam pixels (foam_occlusion_upsample.frag
// spreads it to the rest).
#include "lib/frame.glsl"
#include "lib/environment.glsl"
#include "lib/foam_environment.glsl"
#include "lib/foam_lamps.glsl"

layout(binding = 0) uniform sampler2D foamDepth;  // eye depth, h
layout(binding = 1) uniform sampler2D foamNormal;
layout(binding = 2) uniform sampler2D foamIntensity;
layout(binding = 6) uniform sampler2D irradianceMap;
// Per pixel: foam opacity, foam depth where opaque, liquid depth, solid depth (foam_occluders.frag).
layout(binding = 7) uniform sampler2D occluders;

// The Halton samples in [-1, 1]^3 (xyz) with their length (w) that lie inside the unit sphere, in the
// sequence's order, and how many of the sequence's first n samples those are, [n]: made once by
// FoamOcclusionPass. A pass that takes n samples of the sequence uses the first insideAmongFirst[n] of these;
// the others lie outside the sphere, which the paper skips.
layout(std430, binding = 0) readonly buffer HaltonSamples {
  vec4 haltonSamples[];
};
layout(std430, binding = 2) readonly buffer HaltonInsideCounts {
  uint insideAmongFirst[];
};
// 0: foam pixels, 1: SSAO samples taken (nu summed over passes), 2: estimates made, for the frame's stats.
layout(std430, binding = 1) buffer OcclusionCounters {
  uint occlusionCounters[3];
};

uniform float initialRadiusFactor;    // AOInitSRFac
uniform float radiusIncrementFactor;  // AOSRIncFac
uniform int passes;                   // AO#Passes
uniform float sampleDensity;          // AOSDens
uniform int minSamples;               // AO#MinSamp
uniform int maxSamples;               // AO#MaxSamp
uniform float maxOcclusionDistance;   // AOMaxOcclDist
uniform float liquidOpacity;          // a_i of a liquid occluder
uniform vec3 shadowShape;             // AOShScale, AOShExp, AOShOffset
uniform bool useIrradianceMap;
uniform int blockSize;                // full-resolution pixels along each side of what one invocation estimates

layout(location = 0) out vec2 outShadow;  // zeta, and the eye depth it was estimated at
layout(location = 1) out vec4 outIrradiance;

// delta of one occluder at eye depth `occluderDepth` for the fragment at `fragmentDepth`: the quadratic
// falloff that keeps distant fragments from occluding.
float occlusionRange(float fragmentDepth, float occluderDepth) {
  float falloff = max(1.0 - abs(fragmentDepth - occluderDepth) / maxOcclusionDistance, 0.0);
  return falloff * falloff;
}

// How many Halton samples a pass takes within a search radius of `screenRadius` pixels.
int samplesWithin(float screenRadius) {
  return int(clamp(0.75 * kPi * screenRadius * screenRadius * screenRadius * sampleDensity, float(minSamples),
                   float(maxSamples)));
}

void main() {
  outShadow = vec2(0.0, kNoSurfaceDepth);
  outIrradiance = vec4(0.0);
  // The block's foam pixel nearest the mean depth of its foam. (Its nearest foam pixel, the first choice, is
  // the least occluded: blocks of 2 made the drop example's foam 11 % brighter on average.)
  ivec2 pixel = ivec2(-1);
  float depth = kNoSurfaceDepth;
  uint foamPixels = 0u, pixelsWithDepth = 0u;
  float depthSum = 0.0;
  for (int y = 0; y < blockSize; ++y)
    for (int x = 0; x < blockSize; ++x) {
      ivec2 candidate = ivec2(gl_FragCoord.xy) * blockSize + ivec2(x, y);
      if (any(greaterThanEqual(candidate, ivec2(frame.viewportSize.xy)))) continue;
      if (texelFetch(foamIntensity, candidate, 0).r <= 0.0) continue;
      ++foamPixels;
      float candidateDepth = texelFetch(foamDepth, candidate, 0).r;
      if (candidateDepth >= kNoSurfaceDepth * 0.5) continue;
      ++pixelsWithDepth;
      depthSum += candidateDepth;
    }
  float meanDepth = pixelsWithDepth > 0u ? depthSum / float(pixelsWithDepth) : kNoSurfaceDepth;
  float closest = kNoSurfaceDepth;
  for (int y = 0; y < blockSize; ++y)
    for (int x = 0; x < blockSize; ++x) {
      ivec2 candidate = ivec2(gl_FragCoord.xy) * blockSize + ivec2(x, y);
      if (any(greaterThanEqual(candidate, ivec2(frame.viewportSize.xy)))) continue;
      if (texelFetch(foamIntensity, candidate, 0).r <= 0.0) continue;
      float candidateDepth = texelFetch(foamDepth, candidate, 0).r;
      if (candidateDepth >= kNoSurfaceDepth * 0.5 || !(abs(candidateDepth - meanDepth) < closest)) continue;
      closest = abs(candidateDepth - meanDepth);
      depth = candidateDepth;
      pixel = candidate;
    }
  if (depth >= kNoSurfaceDepth * 0.5) return;
  float searchRadius = texelFetch(foamDepth, pixel, 0).g;
  vec3 position = cameraRayFromFragCoord(vec2(pixel) + 0.5) * depth;
  vec3 worldNormal = normalize(texelFetch(foamNormal, pixel, 0).xyz);
  vec3 cameraNormal = mat3(frame.cameraFromWorld) * worldNormal;
  float worldPerSearchRadius = frame.tanHalfFov.y * depth;  // h is relative to half the screen's height
  float pixelsPerSearchRadius = 0.5 * frame.viewportSize.y;

  float occlusion = 0.0, weights = 0.0;
  vec3 irradiance = vec3(0.0);
  int irradianceSamples = 0;
  uint samplesTaken = 0u;
  // The irradiance from the first pass's samples: a loop of its own, because on llvmpipe code inside an `if`
  // runs for every pixel whether or not the condition holds, so inside the passes' loop its environment
  // lookups cost every pass (docs/frame-cost.md, session 40).
  if (!useIrradianceMap) {
    int inside = int(insideAmongFirst[samplesWithin(searchRadius * initialRadiusFactor * pixelsPerSearchRadius)]);
    for (int i = 0; i < inside; ++i) {
      vec4 unit = haltonSamples[i];
      // The sample's direction, turned into the normal's hemisphere, weighted by its cosine.
      vec3 direction = unit.xyz / unit.w;
      if (dot(direction, cameraNormal) < 0.0) direction = -direction;
      irradiance += environmentRadiance(mat3(frame.worldFromCamera) * direction) * dot(direction, cameraNormal);
      ++irradianceSamples;
    }
  }
  for (int pass = 0; pass < passes; ++pass) {
    float passRadius = searchRadius * (initialRadiusFactor + radiusIncrementFactor * float(pass));
    float screenRadius = passRadius * pixelsPerSearchRadius;
    int count = samplesWithin(screenRadius);
    samplesTaken += uint(count);
    float worldRadius = passRadius * worldPerSearchRadius;
    int inside = int(insideAmongFirst[count]);
    for (int i = 0; i < inside; ++i) {
      vec4 unit = haltonSamples[i];
      vec3 samplePosition = position + worldRadius * unit.xyz;
      float sampleDepth = -samplePosition.z;
      if (sampleDepth <= getNearClip()) continue;
      vec2 sampleFragCoord = fragCoordFromCamera(samplePosition);
      if (!onScreen(sampleFragCoord)) continue;
      ivec2 samplePixel = ivec2(sampleFragCoord);
      float lambda = (1.0 - unit.w) * (1.0 - unit.w);
      weights += lambda;
      // k: the sample lies behind foam, liquid or a solid, each within AOMaxOcclDist of the fragment. a sums
      // the opacities of the fragments in front of it (foam: its intensity), and delta is the nearest one's.
      // Foam of no intensity is not an occluder: it is clear, and the sprite passes need not draw it
      // (foam.cull_hidden), so its depth is not always there.
      vec4 occluder = texelFetch(occluders, samplePixel, 0);
      float foamOpacity = occluder.r, foamOccluder = occluder.g, fluidOccluder = occluder.b,
            solidOccluder = occluder.a;
      float opacity = 0.0, delta = 0.0;
      if (sampleDepth > foamOccluder) {
        float range = occlusionRange(depth, foamOccluder);
        if (range > 0.0) opacity += foamOpacity;
        delta = max(delta, range);
      }
      if (sampleDepth > fluidOccluder) {
        float range = occlusionRange(depth, fluidOccluder);
        if (range > 0.0) opacity += liquidOpacity;
        delta = max(delta, range);
      }
      if (sampleDepth > solidOccluder) {
        float range = occlusionRange(depth, solidOccluder);
        if (range > 0.0) opacity += 1.0;
        delta = max(delta, range);
      }
      occlusion += lambda * delta * min(opacity, 1.0);
    }
  }
  atomicAdd(occlusionCounters[0], foamPixels);
  atomicAdd(occlusionCounters[1], samplesTaken);
  atomicAdd(occlusionCounters[2], 1u);
  float omega = weights > 0.0 ? occlusion / weights : 0.0;
  outShadow = vec2(clamp(pow(omega * shadowShape.x, shadowShape.y) + shadowShape.z, 0.0, 1.0), depth);
  if (useIrradianceMap)
    irradiance = texture(irradianceMap, equirectangularUvFromDirection(worldNormal)).rgb;
  else
    irradiance = irradianceSamples > 0 ? irradiance / float(irradianceSamples) : vec3(0.0);
  irradiance += foamLampIrradiance((frame.worldFromCamera * vec4(position, 1.0)).xyz, worldNormal);
  outIrradiance = vec4(irradiance, 1.0);
}
