#version 450 core
// Caustics, step 1: the path of the light through each vertex of a grid over the light's view of the liquid
// (after Wyman and Davis 2006's caustic maps, in screen space). A light ray enters the liquid's front surface
// as the light sees it (Snell refraction, Fresnel), crosses the liquid to its back surface (found by fixed-point
// iteration on the light's back depth layer) or to a solid inside it (the background's depth), leaves with a
// second refraction, and is marched in the camera's view until it meets the background. Output per vertex: the
// receiver in camera space, the light it carries as a fraction of the light's, and the receiver's position in
// the light's view (for the area the vertex's share of light spreads over).
#include "lib/frame.glsl"
#include "lib/optics.glsl"
#include "lib/light_view.glsl"
#include "lib/screen_trace.glsl"
#include "lib/caustic_receiver.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D backgroundEyeDepth;
layout(binding = 1) uniform sampler2D lightFrontDepth;
layout(binding = 2) uniform sampler2D lightBackDepth;
layout(binding = 3) uniform sampler2D lightFrontNormal;
layout(binding = 4) uniform sampler2D lightBackNormal;

layout(rgba32f, binding = 0) uniform writeonly image2D receiverPosition;  // camera space; w: receiverSeen
layout(rgba32f, binding = 1) uniform writeonly image2D receiverLight;     // carried fraction of the light
layout(rgba32f, binding = 2) uniform writeonly image2D receiverLightTexel;  // xy: texel in the light's view

uniform int gridStep;
uniform float indexOfRefraction;
uniform vec3 absorptionPerUnitLength;

float lightLayer(sampler2D layer, vec2 texel) {
  ivec2 clamped = clamp(ivec2(floor(texel)), ivec2(0), ivec2(lightView.viewportSize.xy) - 1);
  return texelFetch(layer, clamped, 0).r;
}

vec3 lightNormal(sampler2D layer, vec2 texel) {
  ivec2 clamped = clamp(ivec2(floor(texel)), ivec2(0), ivec2(lightView.viewportSize.xy) - 1);
  vec4 normal = texelFetch(layer, clamped, 0);
  return normal.w > 0.0 ? normalize(normal.xyz) : vec3(0.0);
}

vec3 cameraFromWorldPoint(vec3 world) { return (frame.cameraFromWorld * vec4(world, 1.0)).xyz; }

// How far a camera-space point lies behind the background's visible surface (negative in front), or a
// large negative number off screen.
float behindSolid(vec3 cameraPoint) {
  if (-cameraPoint.z <= getNearClip()) return -1e30;
  vec2 pixel = fragCoordFromCamera(cameraPoint);
  if (!onScreen(pixel)) return -1e30;
  return -cameraPoint.z - texelFetch(backgroundEyeDepth, ivec2(pixel), 0).r;
}

// Where a camera-space ray meets the background, or a negative parameter when it leaves the view.
float solidAlong(vec3 origin, vec3 direction) {
  if (-origin.z <= getNearClip() || !onScreen(fragCoordFromCamera(origin))) return -1.0;
  ScreenRay ray = screenRay(origin, direction);
  // The loop brackets the crossing and the bisection runs after it: llvmpipe runs an `if`'s body, and a loop's
  // at least once, for a whole group of invocations, so a bisection inside would cost every sample.
  float previousT = 0.0, t = 0.0;
  bool crossed = false;
  for (int k = 1; k <= ray.samples; ++k) {
    t = screenRaySampleT(ray, k);
    if (behindSolid(origin + t * direction) >= 0.0) {
      crossed = true;
      break;
    }
    previousT = t;
  }
  if (!crossed) return -1.0;
  float low = previousT, high = t;
  for (int i = 0; i < 12; ++i) {
    float middle = 0.5 * (low + high);
    if (behindSolid(origin + middle * direction) >= 0.0) high = middle; else low = middle;
  }
  return high;
}

// The receiver's w: 1 where the camera may see it, 2 where it lies behind the visible surface by more than the
// splat's tolerance (the floor of a pool behind its tank's near wall, seen from outside): caustic_splat.geom
// drops a triangle whose three receivers are hidden. Off screen counts as seen (the triangle may reach in).
float receiverSeen(vec3 receiverCamera) {
  vec2 pixel = fragCoordFromCamera(receiverCamera);
  if (-receiverCamera.z <= getNearClip() || !onScreen(pixel)) return 1.0;
  float visible = texelFetch(backgroundEyeDepth, ivec2(pixel), 0).r;
  if (visible >= kNoSurfaceDepth * 0.5) return 1.0;
  return -receiverCamera.z - visible > causticDepthTolerance(visible) ? 2.0 : 1.0;
}

void main() {
  ivec2 vertex = ivec2(gl_GlobalInvocationID.xy);
  ivec2 gridSize = imageSize(receiverPosition);
  if (any(greaterThanEqual(vertex, gridSize))) return;
  imageStore(receiverPosition, vertex, vec4(0.0));
  imageStore(receiverLight, vertex, vec4(0.0));
  imageStore(receiverLightTexel, vertex, vec4(0.0));
  vec2 texel = min(vec2(vertex * gridStep) + 0.5, lightView.viewportSize.xy - 0.5);
  float front = lightLayer(lightFrontDepth, texel);
  if (front >= kNoSurfaceDepth * 0.5) return;

  // Into the liquid.
  vec3 entry = worldFromLightTexel(texel, front);
  vec3 travel = lightTravelAt(entry);
  vec3 normal = lightNormal(lightFrontNormal, texel);
  if (dot(normal, normal) == 0.0) normal = -travel;
  if (dot(normal, travel) > 0.0) normal = -normal;
  float entryFresnel = schlickFresnel(-dot(normal, travel), indexOfRefraction);
  vec3 inside = refract(travel, normal, 1.0 / indexOfRefraction);

  // To the back surface: the light eye depth along the ray must reach the back layer's depth where the ray
  // is; each step corrects the length by the remaining depth difference.
  vec3 lightAxis = -lightView.worldFromCamera[2].xyz;
  float depthRate = max(dot(inside, lightAxis), 0.05);
  float back = lightLayer(lightBackDepth, texel);
  float pathLength = max(back - front, 0.0) / depthRate;
  for (int i = 0; i < 8; ++i) {
    vec3 point = entry + pathLength * inside;
    float backHere = lightLayer(lightBackDepth, lightTexelFromWorld(point));
    if (backHere >= kNoSurfaceDepth * 0.5) break;  // Stepped past the silhouette: keep the last length.
    pathLength = max(pathLength + (backHere - lightEyeDepthOf(point)) / depthRate, 0.0);
  }
  vec3 exitPoint = entry + pathLength * inside;

  // A solid inside the liquid (the floor of a pool) stops the light before the back surface: a crossing of
  // the background's visible surface along the path, by less than the path's length behind it.
  vec3 entryCamera = cameraFromWorldPoint(entry), exitCamera = cameraFromWorldPoint(exitPoint);
  float tolerance = max(pathLength, 1e-4);
  const int kSolidSamples = 16;
  int blockedSample = 0;  // the first sample behind such a solid; 0: none (bisected after the loop, as above)
  for (int k = 1; k <= kSolidSamples; ++k) {
    float behind = behindSolid(mix(entryCamera, exitCamera, float(k) / float(kSolidSamples)));
    if (behind >= 0.0 && behind < tolerance) {
      blockedSample = k;
      break;
    }
  }
  float blockedAt = -1.0;
  if (blockedSample > 0) {
    float low = float(blockedSample - 1) / float(kSolidSamples), high = float(blockedSample) / float(kSolidSamples);
    for (int i = 0; i < 10; ++i) {
      float middle = 0.5 * (low + high);
      float b = behindSolid(mix(entryCamera, exitCamera, middle));
      if (b >= 0.0 && b < tolerance) high = middle; else low = middle;
    }
    blockedAt = high;
  }

  vec3 receiverCamera;
  vec3 carried;
  if (blockedAt >= 0.0) {
    receiverCamera = mix(entryCamera, exitCamera, blockedAt);
    carried = (1.0 - entryFresnel) * exp(-absorptionPerUnitLength * pathLength * blockedAt);
  } else {
    // Out through the back surface, whose outward normal faces along the ray.
    vec3 backNormal = lightNormal(lightBackNormal, lightTexelFromWorld(exitPoint));
    if (dot(backNormal, backNormal) == 0.0) backNormal = inside;
    if (dot(backNormal, inside) < 0.0) backNormal = -backNormal;
    vec3 outside = refract(inside, -backNormal, indexOfRefraction);
    if (dot(outside, outside) == 0.0) return;  // Totally reflected: this light stays in the liquid.
    float exitFresnel = schlickFresnel(dot(outside, backNormal), indexOfRefraction);
    vec3 outsideCamera = mat3(frame.cameraFromWorld) * outside;
    float t = solidAlong(exitCamera, outsideCamera);
    if (t < 0.0) return;  // The light leaves the view without meeting the background.
    receiverCamera = exitCamera + t * outsideCamera;
    carried = (1.0 - entryFresnel) * (1.0 - exitFresnel) * exp(-absorptionPerUnitLength * pathLength);
  }
  vec3 receiverWorld = (frame.worldFromCamera * vec4(receiverCamera, 1.0)).xyz;
  imageStore(receiverPosition, vertex, vec4(receiverCamera, receiverSeen(receiverCamera)));
  imageStore(receiverLight, vertex, vec4(carried, 0.0));
  imageStore(receiverLightTexel, vertex, vec4(lightTexelFromWorld(receiverWorld), 0.0, 0.0));
}
