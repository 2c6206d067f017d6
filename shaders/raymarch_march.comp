#version 450 core
// Adaptive ray marching (Wu et al., algorithm 1): each ray the tile casts (raymarch_tiles.comp) enters at
// D_all, steps through the binary density grid M (a zero texel skips its 2x2x2 block, a zero bit its cell, a
// marked cell is sampled every `stepLength`), jumps to the aggregates' depth D_agg after maxSkipSteps steps,
// and stops where the density reaches the iso-value, refined by bisection. The normal blends the screen-space
// normal of the smoothed D_all with the kernel gradient (equations 11-16). With `adaptive` false the ray takes
// uniform steps and never jumps (Xiao et al. 2017, the baseline the paper compares against).
layout(local_size_x = 8, local_size_y = 8) in;
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"
#include "lib/raymarch_grid.glsl"

layout(binding = 0) uniform sampler2D allDepth;           // D_all
layout(binding = 1) uniform sampler2D aggregateFrontDepth;  // D_agg
layout(binding = 2) uniform sampler2D splashBackDepth;
layout(binding = 3) uniform sampler2D aggregateBackDepth;
layout(binding = 4) uniform sampler2D backgroundEyeDepth;
layout(binding = 5) uniform sampler2D screenNormal;  // N_screen, from the bilateral-smoothed D_all
layout(binding = 6) uniform usampler2D tileLevels;
layout(binding = 7) uniform usampler3D densityMask;
layout(binding = 0, r32f) uniform writeonly image2D sampleDepth;
layout(binding = 1, rgba16f) uniform writeonly image2D sampleNormal;  // world normal; w: 0 miss, 1 splash, 2 aggregate
layout(binding = 2, r32f) uniform writeonly image2D sampleSteps;
layout(std430, binding = 8) buffer MarchCounters { uint marchCounters[4]; };  // rays, steps, densities, hits

uniform bool adaptive;
uniform float iso;
uniform float stepLength;
uniform int maxSteps;
uniform int maxSkipSteps;
uniform float entryBackoff;   // how far in front of D_all a ray starts, world units
uniform float particleRadius; // r
uniform float distanceWeight; // A of equation 12, per world unit
uniform float sizeWeight;     // B of equation 13, per pixel
uniform int tileSize;
uniform bool hasSplash;
uniform bool hasAggregate;
const int kBisections = 6;
const int kEntryRetreats = 4;

// The ray parameters where the ray enters and leaves a box (entry > exit: it misses).
vec2 boxSpan(vec3 origin, vec3 inverseDirection, vec3 low, vec3 high) {
  vec3 a = (low - origin) * inverseDirection, b = (high - origin) * inverseDirection;
  vec3 near = min(a, b), far = max(a, b);
  return vec2(max(max(near.x, near.y), near.z), min(min(far.x, far.y), far.z));
}

float rayParameter(float eyeDepth, float lengthPerDepth) {
  return hasSurface(eyeDepth) ? eyeDepth * lengthPerDepth : -1.0;
}

void writeSample(ivec2 pixel, float depth, vec4 normalAndClass, float steps) {
  imageStore(sampleDepth, pixel, vec4(depth));
  imageStore(sampleNormal, pixel, normalAndClass);
  imageStore(sampleSteps, pixel, vec4(steps));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(frame.viewportSize.xy)))) return;
  uint level = texelFetch(tileLevels, pixel / tileSize, 0).r;
  int spacing = 1 << level;
  float entryDepth = texelFetch(allDepth, pixel, 0).r;
  if (level == 3u || any(notEqual(pixel % spacing, ivec2(0))) || !hasSurface(entryDepth)) {
    writeSample(pixel, kNoSurfaceDepth, vec4(0.0), 0.0);
    return;
  }
  vec3 cameraRay = cameraRayFromFragCoord(vec2(pixel) + 0.5);
  float lengthPerDepth = length(cameraRay);
  vec3 origin = getCameraWorldPosition();
  vec3 direction = normalize(mat3(frame.worldFromCamera) * cameraRay);
  // A ray along a grid plane would divide by zero: nudge the component (the slab test stays exact enough).
  vec3 inverseDirection = 1.0 / mix(direction, vec3(1e-12), lessThan(abs(direction), vec3(1e-12)));

  float tEntry = entryDepth * lengthPerDepth;
  vec2 grid = boxSpan(origin, inverseDirection, gridOrigin, gridOrigin + vec3(gridSize) * cellSize);
  float t = max(tEntry - entryBackoff, grid.x);
  // No particle reaches beyond the farthest back face by more than h; nothing behind a solid is seen.
  float tEnd = max(rayParameter(texelFetch(splashBackDepth, pixel, 0).r, lengthPerDepth),
                   rayParameter(texelFetch(aggregateBackDepth, pixel, 0).r, lengthPerDepth)) + smoothingRadius;
  tEnd = min(tEnd, grid.y);
  float background = rayParameter(texelFetch(backgroundEyeDepth, pixel, 0).r, lengthPerDepth);
  if (background > 0.0) tEnd = min(tEnd, background);
  float tAggregate = rayParameter(texelFetch(aggregateFrontDepth, pixel, 0).r, lengthPerDepth) - entryBackoff;

  // Where many particles crowd together their iso-surface can lie more than h - r in front of D_all: back up
  // by h until the ray starts outside (each try counts as a step).
  int steps = 0, densities = 0;
  vec3 gradient;
  for (int k = 0; k < kEntryRetreats && t > grid.x; ++k) {
    ++steps;
    ++densities;
    if (densityAt(origin + t * direction, gradient) < iso) break;
    t = max(t - smoothingRadius, grid.x);
  }
  float tOutside = t;  // the last parameter known to lie outside the surface
  t += stepLength;
  bool jumped = !adaptive;
  bool hit = false;
  float epsilon = 1e-4 * cellSize;
  for (int i = 0; i < maxSteps && t <= tEnd; ++i) {
    ++steps;
    if (!jumped && i >= maxSkipSteps) {
      jumped = true;
      if (tAggregate > t) {
        t = tAggregate;
        tOutside = t;
      }
    }
    vec3 position = origin + t * direction;
    if (adaptive) {
      ivec3 cell = clamp(cellOf(position), ivec3(0), gridSize - 1);
      uint bits = texelFetch(densityMask, cell >> 1, 0).r;
      vec3 low, high;
      if (bits == 0u) {  // the whole 2x2x2 block is empty: leave it
        low = gridOrigin + vec3((cell >> 1) * 2) * cellSize;
        high = low + 2.0 * cellSize;
      } else if ((bits & (1u << uint((cell.x & 1) | ((cell.y & 1) << 1) | ((cell.z & 1) << 2)))) == 0u) {
        low = gridOrigin + vec3(cell) * cellSize;
        high = low + cellSize;
      } else {
        low = high = vec3(0.0);
      }
      if (high != low) {
        t = max(t, boxSpan(origin, inverseDirection, low, high).y) + epsilon;
        tOutside = t;
        continue;
      }
    }
    ++densities;
    if (densityAt(position, gradient) >= iso) {
      hit = true;
      break;
    }
    tOutside = t;
    t += stepLength;
  }
  if (hit && t > tOutside) {
    float inside = t;
    for (int k = 0; k < kBisections; ++k) {
      float middle = 0.5 * (tOutside + inside);
      ++densities;
      if (densityAt(origin + middle * direction, gradient) >= iso) inside = middle;
      else tOutside = middle;
    }
    t = inside;
  }
  atomicAdd(marchCounters[0], 1u);
  atomicAdd(marchCounters[1], uint(steps));
  atomicAdd(marchCounters[2], uint(densities));
  if (!hit) {
    writeSample(pixel, kNoSurfaceDepth, vec4(0.0), float(steps));
    return;
  }
  atomicAdd(marchCounters[3], 1u);
  vec3 surface = origin + t * direction;
  float depth = t / lengthPerDepth;
  densityAt(surface, gradient);
  // Equations 12-16: trust the object-space normal where the surface lies far behind the entry (the screen
  // normal describes the entry) and where particles are large on screen (the filter cannot flatten them).
  vec4 screen = texelFetch(screenNormal, pixel, 0);
  float gradientLength = length(gradient);
  vec3 objectNormal = gradientLength > 0.0 ? -gradient / gradientLength : -direction;
  float sizeOnScreen = frame.viewportSize.y * particleRadius / (depth * frame.tanHalfFov.y);  // R, d = 2 r
  float weight = screen.w > 0.0 ? min(distanceWeight * abs(t - tEntry) * exp(sizeWeight * sizeOnScreen), 1.0)
                                : 1.0;
  vec3 normal = normalize(weight * objectNormal + (1.0 - weight) * screen.xyz);
  if (dot(normal, direction) > 0.0) normal = objectNormal;  // never a front surface facing away
  float aggregateDepth = texelFetch(aggregateFrontDepth, pixel, 0).r;
  bool aggregate = hasAggregate && (!hasSplash || (hasSurface(aggregateDepth) &&
                                                   depth >= aggregateDepth - smoothingRadius / lengthPerDepth));
  writeSample(pixel, depth, vec4(normal, aggregate ? 2.0 : 1.0), float(steps));
}
