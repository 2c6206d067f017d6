#version 450 core
// How much sky and bounced light a background point keeps when liquid stands between it and part of its sky:
// the floor beside a block of water, under a floating ball, the wall of a tank above its water line. Drawn at
// a reduced resolution (one sample per `scale` x `scale` pixels, at the block's central pixel), since the
// result varies over the liquid's size, and upsampled by lit_background.frag.
// Light from the sky and the surroundings is taken as uniform: the point keeps the mean, over a fixed set of
// cosine-weighted directions around its normal, of what each direction's straight path lets through: Fresnel
// at every crossing of the liquid's surface (water's hemispherical mean each way) and Beer-Lambert over its
// length in the liquid. The liquid is the sky view's (straight down) depth layers: a point lies in it when it
// is between the front and back layer of its column. A path ends at a solid (a point behind the background's
// depth, as the camera sees it, by less than `solidThickness`). A point that lies in the liquid itself loses
// the light of the liquid above it (lib/submerged_sky.glsl), which each sample takes here, so that the lit
// background only upsamples: computed at every pixel, those four columns took llvmpipe 4.8 of the lit
// background's 11.5 ms on the pool seen from the side (docs/frame-cost.md, session 44). Such a point sees the
// sky only through Snell's window, the cone of directions within the critical angle of straight up: those
// directions keep what the liquid above lets through; beyond the window the surface reflects them totally,
// so they see the surroundings along their path up to the surface and back down; below the horizon they see
// the surroundings through the liquid (docs/liquid.md, "Sky light under water").
// Output: (kept light per channel, the sample's eye depth) for the depth-aware upsampling.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"
#include "lib/optics.glsl"
#include "lib/light_view.glsl"
#include "lib/background_normal.glsl"

layout(binding = 0) uniform sampler2D backgroundEyeDepth;
layout(binding = 1) uniform sampler2D lightFrontDepth;  // the sky's view (bound at binding 2 as lightView)
layout(binding = 2) uniform sampler2D lightBackDepth;

#include "lib/light_column.glsl"

uniform int scale;                  // full-resolution pixels per sample along each axis
uniform int directionCount;         // cosine-weighted directions per sample
uniform vec4 liquidBounds;          // centre, radius: a sphere around all the liquid
uniform vec3 liquidBoxLow;          // and a box around it, tighter for a flat body (a pool)
uniform vec3 liquidBoxHigh;
uniform float skyTexel;             // world length of a texel of the sky view
uniform float shortestStep;         // the march's step: two sky texels (docs/liquid.md)
uniform float submergedTolerance;   // how far below the liquid's drawn bottom a point still lies in it
uniform float solidThickness;       // world depth behind a solid's visible surface that counts as inside it
uniform vec3 absorptionPerUnitLength;
uniform float windowCosine;          // cosine of the critical angle, sqrt(1 - 1 / n^2): Snell's window's edge

#include "lib/submerged_sky.glsl"

layout(location = 0) out vec4 outKept;

const int kMaxStepsPerDirection = 32;
// A path reflected totally at a surface it meets almost level is longer than any body: capped.
const float kLongestReflectedPath = 10.0;
const float kGoldenAngle = 2.39996323;

// A point as the two views that judge it see it: the sky view's clip coordinates and eye depth (is it in the
// liquid?) and the camera's (is it in a solid?). All four are linear along a straight path, so a march carries
// them from its start instead of transforming every step's point.
struct ViewedPoint {
  vec4 skyClip;
  float skyDepth;
  vec4 cameraClip;
  float cameraDepth;
};

// `w`: 1 for a point, 0 for a direction (the change per unit of path).
ViewedPoint viewed(vec3 world, float w) {
  vec4 sky = lightView.cameraFromWorld * vec4(world, w), camera = frame.cameraFromWorld * vec4(world, w);
  return ViewedPoint(lightView.clipFromCamera * sky, -sky.z, frame.clipFromCamera * camera, -camera.z);
}

ViewedPoint advanced(ViewedPoint start, ViewedPoint perUnit, float t) {
  return ViewedPoint(start.skyClip + t * perUnit.skyClip, start.skyDepth + t * perUnit.skyDepth,
                     start.cameraClip + t * perUnit.cameraClip, start.cameraDepth + t * perUnit.cameraDepth);
}

// The sky view's front and back depth over a point (no surface: a front beyond everything).
vec2 skyColumn(ViewedPoint point) {
  vec2 texel = (point.skyClip.xy / point.skyClip.w * 0.5 + 0.5) * lightView.viewportSize.xy;
  if (!insideLightView(texel)) return vec2(kNoSurfaceDepth, 0.0);
  return vec2(texelFetch(lightFrontDepth, ivec2(texel), 0).r, texelFetch(lightBackDepth, ivec2(texel), 0).r);
}

// Whether a point lies in the liquid of its column (`tolerance` below its drawn bottom too).
bool inLiquid(ViewedPoint point, vec2 column, float tolerance) {
  return column.x < 0.5 * kNoSurfaceDepth && point.skyDepth >= column.x && point.skyDepth <= column.y + tolerance;
}

// Whether a point lies inside a solid of the background, as far as the camera's view can tell.
bool inSolid(ViewedPoint point) {
  if (point.cameraDepth <= 0.0) return false;
  vec2 fragCoord = (point.cameraClip.xy / point.cameraClip.w * 0.5 + 0.5) * frame.viewportSize.xy;
  if (!onScreen(fragCoord)) return false;
  float behind = point.cameraDepth - texelFetch(backgroundEyeDepth, ivec2(fragCoord), 0).r;
  return behind > skyTexel && behind < solidThickness;
}

// A right-handed basis around a unit normal (Duff et al. 2017).
mat3 basisAround(vec3 normal) {
  float sign = normal.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (sign + normal.z);
  float b = normal.x * normal.y * a;
  return mat3(vec3(1.0 + sign * normal.x * normal.x * a, sign * b, -sign * normal.x),
              vec3(b, sign + normal.y * normal.y * a, -normal.y), normal);
}

// What one direction's straight path from `origin` lets through: Fresnel where it crosses the liquid's
// surface and Beer-Lambert over its length in the liquid. `startsInLiquid`: the origin lies in the liquid (a
// submerged point), so the path's first stretch is in it, and it crosses a surface once where it leaves it.
vec3 keptAlong(vec3 origin, vec3 direction, bool startsInLiquid) {
  vec3 toCentre = liquidBounds.xyz - origin;
  float along = dot(toCentre, direction);
  float missSquared = dot(toCentre, toCentre) - along * along;
  float halfChordSquared = liquidBounds.w * liquidBounds.w - missSquared;
  if (halfChordSquared <= 0.0) return vec3(1.0);
  float halfChord = sqrt(halfChordSquared);
  // The path is marched where it lies in both the sphere and the box.
  // (A direction along a box face's plane divides by a tiny number rather than by zero: no NaN from 0 x inf.)
  vec3 inverse = 1.0 / mix(vec3(1e-12), direction, greaterThan(abs(direction), vec3(1e-12)));
  vec3 toLow = (liquidBoxLow - origin) * inverse, toHigh = (liquidBoxHigh - origin) * inverse;
  vec3 nearSide = min(toLow, toHigh), farSide = max(toLow, toHigh);
  float start = max(max(along - halfChord, 0.0), max(nearSide.x, max(nearSide.y, nearSide.z)));
  float end = min(along + halfChord, min(farSide.x, min(farSide.y, farSide.z)));
  if (end <= start) return vec3(1.0);
  int steps = int(clamp(ceil((end - start) / shortestStep), 1.0, float(kMaxStepsPerDirection)));
  float stepLength = (end - start) / float(steps);
  float lengthInLiquid = 0.0;
  int crossings = 0;
  bool wasIn = startsInLiquid, inStartingBody = startsInLiquid;
  ViewedPoint first = viewed(origin, 1.0), perUnit = viewed(direction, 0.0);
  for (int i = 0; i < steps; ++i) {
    ViewedPoint point = advanced(first, perUnit, start + (float(i) + 0.5) * stepLength);
    if (inSolid(point)) break;
    // A floor the liquid rests on lies within its drawn bottom's undulation: that gap is the body's too.
    bool isIn = inLiquid(point, skyColumn(point), inStartingBody ? submergedTolerance : 0.0);
    if (isIn) {
      lengthInLiquid += stepLength;
      crossings += wasIn ? 0 : 2;  // in and out again
    } else if (inStartingBody) {
      crossings += 1;  // out of the body it started in
    }
    inStartingBody = inStartingBody && isIn;
    wasIn = isIn;
  }
  return pow(1.0 - kHemisphericalFresnel, float(crossings)) * exp(-absorptionPerUnitLength * lengthInLiquid);
}

void main() {
  ivec2 pixel = min(ivec2(gl_FragCoord.xy) * scale + scale / 2, ivec2(frame.viewportSize.xy) - 1);
  float eyeDepth = texelFetch(backgroundEyeDepth, pixel, 0).r;
  outKept = vec4(1.0, 1.0, 1.0, eyeDepth);
  if (!hasSurface(eyeDepth)) return;
  vec3 world = worldPositionFromFragCoord(vec2(pixel) + 0.5, eyeDepth);
  vec3 normal = backgroundNormal(backgroundEyeDepth, pixel, eyeDepth);
  if (dot(normal, normal) == 0.0) normal = vec3(0.0, 0.0, 1.0);  // a lone pixel: taken as floor
  mat3 basis = basisAround(normalize(normal));
  // Off the surface, so the first steps do not find the solid the point lies on.
  vec3 origin = world + basis[2] * skyTexel;
  ViewedPoint here = viewed(world, 1.0);
  bool submerged = inLiquid(here, skyColumn(here), submergedTolerance);
  // A submerged point: what its window keeps, and its depth below the surface, which a totally reflected
  // path crosses twice.
  vec3 window = submerged ? submergedSkyKept(world) : vec3(1.0);
  float depth = submerged ? depthBelowSurface(world) : 0.0;
  vec3 kept = vec3(0.0);
  for (int i = 0; i < directionCount; ++i) {
    // Malley's method: points spread evenly over the unit disc (a golden-angle spiral), lifted onto the
    // hemisphere, are cosine-distributed.
    float radiusSquared = (float(i) + 0.5) / float(directionCount);
    float angle = float(i) * kGoldenAngle;
    vec3 local = vec3(sqrt(radiusSquared) * vec2(cos(angle), sin(angle)), sqrt(1.0 - radiusSquared));
    vec3 direction = basis * local;
    if (!submerged || direction.z <= 0.0) {
      kept += keptAlong(origin, direction, submerged);
    } else if (direction.z > windowCosine) {
      kept += window;
    } else {
      // Up to the surface (depth / cos) and, reflected, back down to the point's height (as far again), then
      // on as the mirrored direction's own path from the point.
      float upAndDown = min(2.0 * depth / direction.z, kLongestReflectedPath);
      kept += exp(-absorptionPerUnitLength * upAndDown) *
              keptAlong(origin, vec3(direction.xy, -direction.z), true);
    }
  }
  outKept = vec4(kept / float(directionCount), eyeDepth);
}
