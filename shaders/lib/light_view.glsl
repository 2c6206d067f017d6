// A light's view of the liquid (binding 2), laid out as the frame block (FrameUniforms, std140), and the light
// itself: where its rays come from and how strong they are at a point. Requires lib/frame.glsl and
// lib/optics.glsl.
layout(std140, binding = 2) uniform LightViewBlock {
  mat4 clipFromCamera;
  mat4 cameraFromWorld;
  mat4 worldFromCamera;
  vec4 viewportSize;
  vec4 clipPlanes;
  vec4 tanHalfFov;
} lightView;

#include "lib/lamp.glsl"

uniform int lightType;
uniform vec3 lightDirection;  // sun and spot: the way the light travels
uniform vec3 lightPosition;   // spot and point
uniform float lightStrength;  // sun: W/m^2; spot and point: W
uniform float spotCosine;     // cosine of the spot cone's half angle

// The texel position (x right, y up, texel centres at +0.5) of a world point in the light's view.
vec2 lightTexelFromWorld(vec3 world) {
  vec4 clip = lightView.clipFromCamera * (lightView.cameraFromWorld * vec4(world, 1.0));
  return (clip.xy / clip.w * 0.5 + 0.5) * lightView.viewportSize.xy;
}

float lightEyeDepthOf(vec3 world) { return -(lightView.cameraFromWorld * vec4(world, 1.0)).z; }

vec3 worldFromLightTexel(vec2 texel, float eyeDepth) {
  vec2 ndc = texel * lightView.viewportSize.zw * 2.0 - 1.0;
  return (lightView.worldFromCamera * vec4(vec3(ndc * lightView.tanHalfFov.xy, -1.0) * eyeDepth, 1.0)).xyz;
}

// The world length of the light's ray through a texel per unit of eye depth along it (the view is rigid): the
// distance between two points of that ray is their depth difference times this.
float lightRayLengthPerDepth(vec2 texel) {
  vec2 ndc = texel * lightView.viewportSize.zw * 2.0 - 1.0;
  return length(vec3(ndc * lightView.tanHalfFov.xy, 1.0));
}

bool insideLightView(vec2 texel) {
  return all(greaterThanEqual(texel, vec2(0.0))) && all(lessThan(texel, lightView.viewportSize.xy));
}

// The unit direction the light travels in when it reaches a world point.
vec3 lightTravelAt(vec3 world) { return lampTravelAt(lightType, lightDirection, lightPosition, world); }

// Irradiance the light would give a surface facing it at a world point, without the liquid (W/m^2).
float lightIrradianceAt(vec3 world) {
  return lampIrradianceAt(lightType, lightDirection, lightPosition, lightStrength, spotCosine, world);
}

uniform vec3 lightColor;

// The weight of this light in the mix of every light's direct light at a point: its irradiance there (the
// colour's mean stands for the colour).
float lightWeightAt(vec3 world) { return lightIrradianceAt(world) * dot(lightColor, vec3(1.0 / 3.0)); }
