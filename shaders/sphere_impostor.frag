#version 450 core
// Exact ray-sphere intersection per pixel: planar eye depth, world normal and gl_FragDepth of the nearest
// sphere, hidden by the background's solids.
#include "lib/frame.glsl"

layout(binding = 0) uniform sampler2D backgroundEyeDepth;

flat in vec4 vCameraSphere;

layout(location = 0) out float outEyeDepth;
layout(location = 1) out vec4 outNormal;  // xyz: world normal, w: coverage

void main() {
  vec3 direction = normalize(cameraRayFromFragCoord(gl_FragCoord.xy));
  vec3 centre = vCameraSphere.xyz;
  float radius = vCameraSphere.w;
  // The discriminant from the perpendicular distance, and the near root as c / (b + sqrt(disc)): both stay
  // accurate for spheres thousands of radii away, where b^2 - c cancels catastrophically.
  float along = dot(direction, centre);
  vec3 perpendicular = centre - along * direction;
  float discriminant = radius * radius - dot(perpendicular, perpendicular);
  if (discriminant < 0.0 || along <= 0.0) discard;
  float distanceToCentre = length(centre);
  float t = (distanceToCentre - radius) * (distanceToCentre + radius) / (along + sqrt(discriminant));
  vec3 hit = direction * t;
  float eyeDepth = -hit.z;
  if (eyeDepth < getNearClip() || eyeDepth > getFarClip()) discard;
  if (eyeDepth >= texelFetch(backgroundEyeDepth, ivec2(gl_FragCoord.xy), 0).r) discard;

  outEyeDepth = eyeDepth;
  outNormal = vec4(normalize(mat3(frame.worldFromCamera) * ((hit - centre) / radius)), 1.0);
  gl_FragDepth = depthBufferFromEyeDepth(eyeDepth);
}
