#version 450 core
// Back to full resolution (adaptive ray marching paper, 4.3): a pixel that cast no ray takes its surface from
// the rays cast at the corners of its tile's lattice (spacing 2 or 4), bilinearly weighted. Corners that
// missed outvote the hits when their weight is larger (a silhouette), and only corners of the nearest hit's
// class are blended, so a splash is never averaged with the body behind it. Then the marched first surface is
// written into the front layers the refraction pass reads: as the splash front or the aggregate front by its
// class, the other class's front kept only where it lies behind. A drawn splash sphere in front of the marched
// surface is kept as the surface.
layout(local_size_x = 8, local_size_y = 8) in;
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"

layout(binding = 0) uniform sampler2D sampleDepth;
layout(binding = 1) uniform sampler2D sampleNormal;  // w: 0 miss, 1 splash, 2 aggregate
layout(binding = 2) uniform usampler2D tileLevels;
layout(binding = 3) uniform sampler2D splashFrontDepth;
layout(binding = 4) uniform sampler2D splashFrontNormal;
layout(binding = 5) uniform sampler2D aggregateFrontDepth;
layout(binding = 6) uniform sampler2D aggregateFrontNormal;
layout(binding = 0, r32f) uniform writeonly image2D outSplashDepth;
layout(binding = 1, rgba16f) uniform writeonly image2D outSplashNormal;
layout(binding = 2, r32f) uniform writeonly image2D outAggregateDepth;
layout(binding = 3, rgba16f) uniform writeonly image2D outAggregateNormal;

uniform int tileSize;

// Whether a ray was cast at a lattice point of spacing 2^level.
bool wasCast(ivec2 point, uint level) {
  if (any(lessThan(point, ivec2(0))) || any(greaterThanEqual(point, ivec2(frame.viewportSize.xy)))) return false;
  uint castLevel = texelFetch(tileLevels, point / tileSize, 0).r;
  return castLevel <= level;  // spacings divide each other: a point of the coarse lattice is on every finer one
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.viewportSize.xy)))) return;
  uint level = texelFetch(tileLevels, pixel / tileSize, 0).r;
  float depth = kNoSurfaceDepth;
  vec4 normal = vec4(0.0);
  if (level < 3u) {
    int spacing = 1 << level;
    ivec2 base = pixel / spacing * spacing;
    vec2 fraction = vec2(pixel - base) / float(spacing);
    ivec2 corners[4] = ivec2[4](base, base + ivec2(spacing, 0), base + ivec2(0, spacing), base + ivec2(spacing));
    float weights[4] = float[4]((1.0 - fraction.x) * (1.0 - fraction.y), fraction.x * (1.0 - fraction.y),
                                (1.0 - fraction.x) * fraction.y, fraction.x * fraction.y);
    float hitWeight = 0.0, missWeight = 0.0, nearest = -1.0;
    float nearestClass = 0.0;
    for (int i = 0; i < 4; ++i) {
      if (weights[i] <= 0.0 || !wasCast(corners[i], level)) continue;
      float surfaceClass = texelFetch(sampleNormal, corners[i], 0).w;
      if (surfaceClass > 0.5) {
        hitWeight += weights[i];
        if (weights[i] > nearest) {
          nearest = weights[i];
          nearestClass = surfaceClass;
        }
      } else {
        missWeight += weights[i];
      }
    }
    if (hitWeight > missWeight) {
      float depthSum = 0.0, weightSum = 0.0;
      vec3 normalSum = vec3(0.0);
      for (int i = 0; i < 4; ++i) {
        if (weights[i] <= 0.0 || !wasCast(corners[i], level)) continue;
        vec4 cornerNormal = texelFetch(sampleNormal, corners[i], 0);
        if (abs(cornerNormal.w - nearestClass) > 0.5) continue;
        depthSum += weights[i] * texelFetch(sampleDepth, corners[i], 0).r;
        normalSum += weights[i] * cornerNormal.xyz;
        weightSum += weights[i];
      }
      depth = depthSum / weightSum;
      normal = vec4(length(normalSum) > 0.0 ? normalize(normalSum) : vec3(0.0, 0.0, 1.0), nearestClass);
    }
  }
  float splashBehind = texelFetch(splashFrontDepth, pixel, 0).r;
  float aggregateBehind = texelFetch(aggregateFrontDepth, pixel, 0).r;
  // A drawn splash is the sphere of Mantaflow's surface around it (or of (1 + offset) r): the marched
  // surface, whose kernels are capped at the body's support, is never smaller. Where the sphere stands in
  // front of the marched surface, it is the surface.
  if (hasSurface(splashBehind) && (normal.w <= 0.5 || splashBehind < depth)) {
    depth = splashBehind;
    normal = vec4(texelFetch(splashFrontNormal, pixel, 0).xyz, 1.0);
  }
  bool hit = normal.w > 0.5;
  bool splash = hit && normal.w < 1.5;
  vec4 none = vec4(0.0);
  if (!hit) {
    imageStore(outSplashDepth, pixel, vec4(kNoSurfaceDepth));
    imageStore(outSplashNormal, pixel, none);
    imageStore(outAggregateDepth, pixel, vec4(kNoSurfaceDepth));
    imageStore(outAggregateNormal, pixel, none);
  } else if (splash) {
    bool keep = hasSurface(aggregateBehind) && aggregateBehind > depth;
    imageStore(outSplashDepth, pixel, vec4(depth));
    imageStore(outSplashNormal, pixel, vec4(normal.xyz, 1.0));
    imageStore(outAggregateDepth, pixel, vec4(keep ? aggregateBehind : kNoSurfaceDepth));
    imageStore(outAggregateNormal, pixel, keep ? texelFetch(aggregateFrontNormal, pixel, 0) : none);
  } else {
    bool keep = hasSurface(splashBehind) && splashBehind > depth;
    imageStore(outAggregateDepth, pixel, vec4(depth));
    imageStore(outAggregateNormal, pixel, vec4(normal.xyz, 1.0));
    imageStore(outSplashDepth, pixel, vec4(keep ? splashBehind : kNoSurfaceDepth));
    imageStore(outSplashNormal, pixel, keep ? texelFetch(splashFrontNormal, pixel, 0) : none);
  }
}
