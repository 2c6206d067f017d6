#version 450 core
// Exact ray-ellipsoid intersection per pixel: the planar eye depth, world normal and gl_FragDepth of the
// nearest front-facing surface (backFaces = false, depth test LESS) or the farthest back-facing surface
// (backFaces = true, depth test GREATER). Ellipsoids whose front lies behind the background's solids are
// hidden; a visible one keeps its back surface even where a solid cuts it, and the refraction pass clips the
// path at the solid.
#include "lib/frame.glsl"

layout(binding = 0) uniform sampler2D backgroundEyeDepth;

uniform bool backFaces;

flat in vec3 vCameraCentre;
flat in mat3 vInverseAxesCamera;

layout(location = 0) out float outEyeDepth;
layout(location = 1) out vec4 outNormal;  // xyz: world outward normal, w: coverage

void main() {
  vec3 direction = normalize(cameraRayFromFragCoord(gl_FragCoord.xy));
  // In the ellipsoid's unit-sphere space the ray is o + t d with o = -A^-1 c. Solving around the closest
  // approach t0 = -(o.d)/(d.d) keeps the discriminant accurate thousands of radii away, where the textbook
  // b^2 - ac cancels catastrophically.
  vec3 origin = -(vInverseAxesCamera * vCameraCentre);
  vec3 unitDirection = vInverseAxesCamera * direction;
  float a = dot(unitDirection, unitDirection);
  float closest = -dot(origin, unitDirection) / a;
  vec3 closestPoint = origin + closest * unitDirection;
  float halfChordSquared = (1.0 - dot(closestPoint, closestPoint)) / a;
  if (halfChordSquared < 0.0) discard;
  float halfChord = sqrt(halfChordSquared);
  float nearT = closest - halfChord;
  if (nearT <= 0.0) discard;  // The camera is inside or past the ellipsoid; the CPU culls these.
  float t = backFaces ? closest + halfChord : nearT;

  float nearDepth = nearT * -direction.z;
  if (nearDepth < getNearClip() || nearDepth >= texelFetch(backgroundEyeDepth, ivec2(gl_FragCoord.xy), 0).r)
    discard;
  float eyeDepth = t * -direction.z;
  if (eyeDepth > getFarClip()) discard;

  // The gradient of |A^-1 x|^2 is A^-T A^-1 x: the outward normal.
  vec3 unitPoint = origin + t * unitDirection;
  vec3 cameraNormal = normalize(transpose(vInverseAxesCamera) * unitPoint);
  outEyeDepth = eyeDepth;
  outNormal = vec4(normalize(mat3(frame.worldFromCamera) * cameraNormal), 1.0);
  gl_FragDepth = depthBufferFromEyeDepth(eyeDepth);
}
