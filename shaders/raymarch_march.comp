#version 450 core
// Adaptive ray marching (Wu et al., algorithm 1): each ray the tile casts (raymarch_tiles.comp) enters at
// D_all, steps through the binary density grid M (a zero texel skips its 2x2x2 block, a zero bit its cell),
// jumps to the aggregates' depth D_agg after maxSkipSteps steps, and stops where the density reaches the
// iso-value. In a marked cell each density sample also bounds the density along the ray ahead of it (the
// paper's future work, "step lengths from the density of the previous step"): the ray skips the stretch the
// bound proves empty and samples one `stepLength` beyond it; a bracketed crossing is refined by bisection and a
// secant.
// The normal blends the screen-space normal of the smoothed D_all with the kernel gradient (equations 11-16).
// With `adaptive` false the ray takes uniform steps of `stepLength`, never jumps and stops at the first sample
// at or above the iso-value (Xiao et al. 2017, the baseline the paper compares against).
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
// rays, steps, densities, hits, refinement densities, particles visited by the densities (low, high word)
layout(std430, binding = 8) buffer MarchCounters { uint marchCounters[7]; };

// Compiled with and without ADAPTIVE_STEPS (RaymarchPass), not switched by a uniform: llvmpipe runs both sides
// of a branch, so every adaptive sample paid for the uniform march's density as well (142 against 136 ms on the
// dam break; docs/frame-cost.md, session 40).
#ifdef ADAPTIVE_STEPS
const bool adaptive = true;
#else
const bool adaptive = false;
#endif
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
// A Mantaflow domain's box (ellipsoid_impostor.frag clips the drawn liquid to it the same way): rays march
// only inside it, and where the density is already at the iso-value where a ray enters it, the surface is
// the box's face, as Mantaflow's mesh closes the liquid at the walls.
uniform bool clipToDomain;
uniform mat4 domainFromWorld;
uniform vec3 domainLow;
uniform vec3 domainHigh;
const int kBisections = 3;  // adaptive stepping: a bracket of one stepLength refined to 1/8 (then a secant)
const int kEntryRetreats = 4;
const int kReachCells = 1;  // how many cells beyond its own one density sample bounds
// The segment lengths, in steps, that one density sample tests (the nearer and the farther four).
const vec4 kBoundStepsNear = vec4(1.0, 2.0, 4.0, 6.0), kBoundStepsFar = vec4(8.0, 10.0, 13.0, 17.0);

// The ray parameters where the ray enters and leaves a box (entry > exit: it misses).
vec2 boxSpan(vec3 origin, vec3 inverseDirection, vec3 low, vec3 high) {
  vec3 a = (low - origin) * inverseDirection, b = (high - origin) * inverseDirection;
  vec3 near = min(a, b), far = max(a, b);
  return vec2(max(max(near.x, near.y), near.z), min(min(far.x, far.y), far.z));
}

float rayParameter(float eyeDepth, float lengthPerDepth) {
  return hasSurface(eyeDepth) ? eyeDepth * lengthPerDepth : -1.0;
}

uint particlesVisited = 0u;

// The density at the ray's point `t` (as densityAt) and how far the ray may go from there without meeting the
// iso-surface: the longest of the segments [t, t + k stepLength], k one of kBoundSteps, along which the density
// stays below `iso`. Each particle's kernel falls off with distance, so along a segment it adds at most its
// kernel at the segment's nearest point; the sum of those is an upper bound of the density anywhere on the
// segment. The particles within h of a segment are those of the 3x3x3 cells around each cell the segment
// crosses: the point's cell's 27, and for each of the next kReachCells cells along the ray the 3x3 layer that
// its block adds beyond the previous ones (a step along an axis adds the block's face on that side). Segments
// end where the ray leaves the last of those cells.
// Why eight fixed lengths and one cell ahead: on llvmpipe the bound costs arithmetic per particle visited, and a
// bound for every whole step (an array indexed per particle) made each sample cost seven plain densities.
// Eight lengths in two vec4s cost a fixed few operations per particle; a ray takes about 0.7 samples more
// (docs/raymarch.md, "The bound's cost").
float densityAndReach(vec3 origin, vec3 inverseDirection, vec3 direction, float t, out vec3 gradient,
                      out float safe) {
  vec3 position = origin + t * direction;
  ivec3 centre = cellOf(position);
  // The next cells along the ray (3D DDA) and the layer each adds: its cell one step further along the axis
  // the ray crossed, spread over the other two axes.
  ivec3 signs = ivec3(greaterThanEqual(direction, vec3(0.0))) * 2 - 1;
  vec3 cellLow = gridOrigin + vec3(centre) * cellSize;
  vec3 exits = (cellLow + vec3(greaterThanEqual(direction, vec3(0.0))) * cellSize - origin) * inverseDirection;
  vec3 crossing = cellSize * abs(inverseDirection);
  ivec3 cell = centre;
  ivec3 layerBase[kReachCells];
  int layerAxis[kReachCells];
  for (int n = 0; n < kReachCells; ++n) {
    int axis = exits.x <= exits.y ? (exits.x <= exits.z ? 0 : 2) : (exits.y <= exits.z ? 1 : 2);
    cell[axis] += signs[axis];
    exits[axis] += crossing[axis];
    layerBase[n] = cell;
    layerBase[n][axis] += signs[axis];
    layerAxis[n] = axis;
  }
  float reachSteps = (min(min(exits.x, exits.y), exits.z) - t) / stepLength;

  gradient = vec3(0.0);
  float density = 0.0;
  float boundBehind = 0.0;  // what particles behind the point add to every segment: their kernel at the point
  vec4 boundNear = vec4(0.0), boundFar = vec4(0.0);
  for (int m = 0; m < 27 + 9 * kReachCells; ++m) {
    ivec3 visit;
    if (m < 27) {
      visit = centre + ivec3(m % 3, (m / 3) % 3, m / 9) - 1;
    } else {
      int n = (m - 27) / 9, spread = (m - 27) % 9;
      int axis = layerAxis[n];
      visit = layerBase[n];
      visit[(axis + 1) % 3] += spread % 3 - 1;
      visit[(axis + 2) % 3] += spread / 3 - 1;
    }
    if (!insideGrid(visit)) continue;
    int index = cellIndex(visit);
    uint begin = cellStart[index];
    uint end = begin + cellCount[index];
    particlesVisited += end - begin;
    for (uint j = begin; j < end; ++j) {
      vec4 particle = sortedParticles[j];
      vec3 offset = particle.xyz - position;
      float squaredRadius = particle.w * particle.w;  // the particle's own support h_j
      float inverseSquaredRadius = 1.0 / squaredRadius;
      float squaredDistance = dot(offset, offset);
      if (squaredDistance < squaredRadius) {
        float falloff = 1.0 - squaredDistance * inverseSquaredRadius;
        density += falloff * falloff * falloff;
        gradient += 6.0 * falloff * falloff * inverseSquaredRadius * offset;
      }
      float along = dot(offset, direction);
      float squaredAside = max(squaredDistance - along * along, 0.0);
      if (along <= 0.0) {  // nearest to the point on every segment
        if (squaredDistance < squaredRadius) {
          float falloff = 1.0 - squaredDistance * inverseSquaredRadius;
          boundBehind += falloff * falloff * falloff;
        }
        continue;
      }
      if (squaredAside >= squaredRadius) continue;
      vec4 aheadNear = max(along - kBoundStepsNear * stepLength, 0.0);
      vec4 aheadFar = max(along - kBoundStepsFar * stepLength, 0.0);
      vec4 falloffNear = max(1.0 - (squaredAside + aheadNear * aheadNear) * inverseSquaredRadius, 0.0);
      vec4 falloffFar = max(1.0 - (squaredAside + aheadFar * aheadFar) * inverseSquaredRadius, 0.0);
      boundNear += falloffNear * falloffNear * falloffNear;
      boundFar += falloffFar * falloffFar * falloffFar;
    }
  }
  // The bounds grow with the segment's length: the longest segment within reach whose bound stays below iso.
  vec4 safeNear = vec4(lessThan(boundNear + boundBehind, vec4(iso))) *
                  vec4(lessThanEqual(kBoundStepsNear, vec4(reachSteps)));
  vec4 safeFar = vec4(lessThan(boundFar + boundBehind, vec4(iso))) *
                 vec4(lessThanEqual(kBoundStepsFar, vec4(reachSteps)));
  vec4 longest = max(kBoundStepsNear * safeNear, kBoundStepsFar * safeFar);
  safe = max(max(longest.x, longest.y), max(longest.z, longest.w)) * stepLength;
  return density;
}

// densityAt, its particles counted.
float countedDensity(vec3 position, out vec3 gradient) {
  ivec3 centre = cellOf(position);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 cell = centre + ivec3(dx, dy, dz);
        if (insideGrid(cell)) particlesVisited += cellCount[cellIndex(cell)];
      }
  return densityAt(position, gradient);
}

// A sample of the march: the density and, with adaptive steps, how far ahead the ray is known to stay outside.
float sampleDensity(vec3 origin, vec3 inverseDirection, vec3 direction, float t, out vec3 gradient,
                    out float safe) {
  safe = 0.0;
  return adaptive ? densityAndReach(origin, inverseDirection, direction, t, gradient, safe)
                  : countedDensity(origin + t * direction, gradient);
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
  // The part of the ray the surface may lie on: inside the grid and, for a Mantaflow liquid, its domain box
  // (an affine map keeps the ray's parameter).
  vec2 span = grid;
  vec3 boxFaceNormal = vec3(0.0);
  if (clipToDomain) {
    vec3 boxOrigin = (domainFromWorld * vec4(origin, 1.0)).xyz;
    vec3 boxDirection = mat3(domainFromWorld) * direction;
    vec3 inverseBoxDirection =
        1.0 / mix(boxDirection, vec3(1e-12), lessThan(abs(boxDirection), vec3(1e-12)));
    vec3 tLow = (domainLow - boxOrigin) * inverseBoxDirection, tHigh = (domainHigh - boxOrigin) * inverseBoxDirection;
    vec3 tEnter = min(tLow, tHigh), tLeave = max(tLow, tHigh);
    float enter = max(tEnter.x, max(tEnter.y, tEnter.z)), leave = min(tLeave.x, min(tLeave.y, tLeave.z));
    int axis = enter == tEnter.x ? 0 : (enter == tEnter.y ? 1 : 2);
    vec3 faceInBox = vec3(0.0);
    faceInBox[axis] = -sign(boxDirection[axis]);
    boxFaceNormal = normalize(transpose(mat3(domainFromWorld)) * faceInBox);  // normals map by the inverse transpose
    span = vec2(max(grid.x, enter), min(grid.y, leave));
  }
  float t = max(tEntry - entryBackoff, span.x);
  // No particle reaches beyond the farthest back face by more than h; nothing behind a solid is seen.
  float tEnd = max(rayParameter(texelFetch(splashBackDepth, pixel, 0).r, lengthPerDepth),
                   rayParameter(texelFetch(aggregateBackDepth, pixel, 0).r, lengthPerDepth)) + smoothingRadius;
  tEnd = min(tEnd, span.y);
  float background = rayParameter(texelFetch(backgroundEyeDepth, pixel, 0).r, lengthPerDepth);
  if (background > 0.0) tEnd = min(tEnd, background);
  float tAggregate = rayParameter(texelFetch(aggregateFrontDepth, pixel, 0).r, lengthPerDepth) - entryBackoff;

  // Where many particles crowd together their iso-surface can lie more than h - r in front of D_all: back up
  // by h until the ray starts outside (each try counts as a step).
  int steps = 0, densities = 0, refinements = 0;
  vec3 gradient, insideGradient = vec3(0.0);
  float safe = 0.0;
  float density = 0.0;
  bool onBox = false;
  for (int k = 0; k < kEntryRetreats && t >= span.x; ++k) {
    ++steps;
    ++densities;
    density = sampleDensity(origin, inverseDirection, direction, t, gradient, safe);
    if (density < iso) break;
    safe = 0.0;
    // Inside already where the ray enters the domain's box: the surface is the box's face.
    if (clipToDomain && t <= span.x && span.x > grid.x) {
      onBox = true;
      break;
    }
    if (t <= span.x) break;
    t = max(t - smoothingRadius, span.x);
  }
  // Between tOutside and t the surface may lie; before tOutside the ray is known to be outside. outsideDensity
  // is the density at tOutside where it was sampled (-1 where a skip, a bound or the jump put it there).
  float tOutside = t + safe;
  float outsideDensity = safe > 0.0 || density >= iso ? -1.0 : density;  // still inside after the retreats
  t = tOutside + stepLength;
  bool jumped = !adaptive;
  bool hit = onBox;
  float epsilon = 1e-4 * cellSize;
  for (int i = 0; i < maxSteps && t <= tEnd && !onBox; ++i) {
    ++steps;
    if (!jumped && i >= maxSkipSteps) {
      jumped = true;
      if (tAggregate > t) {
        t = tAggregate;
        tOutside = t;
        outsideDensity = -1.0;
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
        outsideDensity = -1.0;
        continue;
      }
    }
    ++densities;
    density = sampleDensity(origin, inverseDirection, direction, t, gradient, safe);
    if (density >= iso) {
      hit = true;
      insideGradient = gradient;
      break;
    }
    // The bound proves [t, t + safe] outside: the next sample is one step beyond it.
    tOutside = t + safe;
    outsideDensity = safe > 0.0 ? -1.0 : density;
    t = tOutside + stepLength;
  }
  if (onBox) t = span.x;
  if (hit && !onBox && adaptive && t > tOutside) {
    // Bisection, then the secant through the bracket's ends where both densities are known.
    float inside = t, insideDensity = density;
    for (int k = 0; k < kBisections; ++k) {
      float middle = 0.5 * (tOutside + inside);
      ++densities;
      ++refinements;
      float value = countedDensity(origin + middle * direction, gradient);
      if (value >= iso) {
        inside = middle;
        insideDensity = value;
        insideGradient = gradient;
      } else {
        tOutside = middle;
        outsideDensity = value;
      }
    }
    t = outsideDensity >= 0.0 && insideDensity > outsideDensity
            ? mix(tOutside, inside, (iso - outsideDensity) / (insideDensity - outsideDensity))
            : 0.5 * (tOutside + inside);
  }
  atomicAdd(marchCounters[0], 1u);
  atomicAdd(marchCounters[1], uint(steps));
  atomicAdd(marchCounters[2], uint(densities));
  atomicAdd(marchCounters[4], uint(refinements));
  if (atomicAdd(marchCounters[5], particlesVisited) + particlesVisited < particlesVisited)
    atomicAdd(marchCounters[6], 1u);  // the low word wrapped
  if (!hit) {
    writeSample(pixel, kNoSurfaceDepth, vec4(0.0), float(steps));
    return;
  }
  atomicAdd(marchCounters[3], 1u);
  vec3 surface = origin + t * direction;
  float depth = t / lengthPerDepth;
  gradient = insideGradient;  // the kernel gradient at the last sample found inside, within 1/8 step of t
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
  if (onBox) normal = boxFaceNormal;
  float aggregateDepth = texelFetch(aggregateFrontDepth, pixel, 0).r;
  bool aggregate = hasAggregate && (!hasSplash || (hasSurface(aggregateDepth) &&
                                                   depth >= aggregateDepth - smoothingRadius / lengthPerDepth));
  writeSample(pixel, depth, vec4(normal, aggregate ? 2.0 : 1.0), float(steps));
}
