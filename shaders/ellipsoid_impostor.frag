#version 450 core
// Exact ray-ellipsoid intersection per pixel: the planar eye depth, world normal and gl_FragDepth of the
// nearest front-facing surface (backFaces = false, depth test LESS) or the farthest back-facing surface
// (backFaces = true, depth test GREATER). Ellipsoids whose front lies behind the background's solids are
// hidden; a visible one keeps its back surface even where a solid cuts it, and the refraction pass clips the
// path at the solid.
#include "lib/frame.glsl"

layout(binding = 0) uniform sampler2D backgroundEyeDepth;

uniform bool backFaces;
// A Mantaflow domain's box (its cache-to-world frame, whose unit is the world's): the liquid is clipped to it,
// so liquid pressed against the domain's walls ends in the flat face Mantaflow's mesh closes it with.
uniform bool clipToDomain;
uniform mat4 domainFromWorld;
uniform mat4 domainFromCamera;  // domainFromWorld x the view's worldFromCamera, once per draw
uniform vec3 domainLow;
uniform vec3 domainHigh;

flat in vec3 vUnitSphereCamera;
flat in mat3 vInverseAxesCamera;

layout(location = 0) out float outEyeDepth;
layout(location = 1) out vec4 outNormal;  // xyz: world outward normal, w: coverage

void main() {
  vec3 direction = normalize(cameraRayFromFragCoord(gl_FragCoord.xy));
  // In the ellipsoid's unit-sphere space the ray is o + t d with o = -A^-1 c. Solving around the closest
  // approach t0 = -(o.d)/(d.d) keeps the discriminant accurate thousands of radii away, where the textbook
  // b^2 - ac cancels catastrophically.
  vec3 origin = vUnitSphereCamera;
  vec3 unitDirection = vInverseAxesCamera * direction;
  float a = dot(unitDirection, unitDirection);
  float closest = -dot(origin, unitDirection) / a;
  vec3 closestPoint = origin + closest * unitDirection;
  float halfChordSquared = (1.0 - dot(closestPoint, closestPoint)) / a;
  if (halfChordSquared < 0.0) discard;
  float halfChord = sqrt(halfChordSquared);
  float nearT = closest - halfChord;
  float farT = closest + halfChord;
  if (farT <= 0.0) discard;  // The ellipsoid lies behind the camera.
  // A camera inside the ellipsoid (the camera under water) sees only its back surface.
  bool cameraInside = nearT <= 0.0;
  if (cameraInside && !backFaces) discard;

  // Clip the chord [nearT, farT] to the domain's box (slab test in the box's frame); where the box cuts the
  // ellipsoid the surface is the box's face, with its normal.
  vec3 boxNormal = vec3(0.0);
  bool onBox = false;
  if (clipToDomain) {
    vec3 boxOrigin = (domainFromCamera * vec4(0.0, 0.0, 0.0, 1.0)).xyz;
    vec3 boxDirection = mat3(domainFromCamera) * direction;
    vec3 inverse = 1.0 / boxDirection;
    vec3 tLow = (domainLow - boxOrigin) * inverse, tHigh = (domainHigh - boxOrigin) * inverse;
    vec3 tEnter = min(tLow, tHigh), tLeave = max(tLow, tHigh);
    float enter = max(tEnter.x, max(tEnter.y, tEnter.z)), leave = min(tLeave.x, min(tLeave.y, tLeave.z));
    float clippedNear = max(nearT, enter), clippedFar = min(farT, leave);
    if (!(clippedNear < clippedFar)) discard;
    if (!backFaces && enter > nearT) {
      int axis = enter == tEnter.x ? 0 : (enter == tEnter.y ? 1 : 2);
      boxNormal[axis] = -sign(boxDirection[axis]);
      onBox = true;
    } else if (backFaces && leave < farT) {
      int axis = leave == tLeave.x ? 0 : (leave == tLeave.y ? 1 : 2);
      boxNormal[axis] = sign(boxDirection[axis]);
      onBox = true;
    }
    nearT = clippedNear;
    farT = clippedFar;
    if (farT <= 0.0 || (nearT <= 0.0 && !backFaces)) discard;
    cameraInside = nearT <= 0.0;
  }
  float t = backFaces ? farT : nearT;

  float nearDepth = cameraInside ? getNearClip() : nearT * -direction.z;
  if (nearDepth < getNearClip() || nearDepth >= texelFetch(backgroundEyeDepth, ivec2(gl_FragCoord.xy), 0).r)
    discard;
  float eyeDepth = t * -direction.z;
  if (eyeDepth > getFarClip() || eyeDepth < getNearClip()) discard;

  // The gradient of |A^-1 x|^2 is A^-T A^-1 x: the outward normal.
  vec3 unitPoint = origin + t * unitDirection;
  vec3 cameraNormal = normalize(transpose(vInverseAxesCamera) * unitPoint);
  // The box frame is a rotation of the world's (unit scale), so its normals turn into the world's by the
  // transpose of its rotation.
  vec3 worldNormal = onBox ? transpose(mat3(domainFromWorld)) * boxNormal : mat3(frame.worldFromCamera) * cameraNormal;
  outEyeDepth = eyeDepth;
  outNormal = vec4(normalize(worldNormal), 1.0);
  gl_FragDepth = depthBufferFromEyeDepth(eyeDepth);
}
