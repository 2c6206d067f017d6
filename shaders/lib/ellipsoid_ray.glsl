// The exact ray cast of one liquid ellipsoid at a pixel, shared by the impostor pass (which keeps the depth
// and the ellipsoid's index) and its normal resolve (which repeats the cast for the winning ellipsoid only).
// Needs lib/frame.glsl.

struct Ellipsoid {
  vec4 centreAndBoundingRadius;  // world centre, radius of a containing sphere
  vec4 inverseAxesRows[3];       // rows of the world-space inverse axes matrix
};

layout(std430, binding = 0) readonly buffer Ellipsoids {
  Ellipsoid ellipsoids[];
};

uniform bool backFaces;
// A Mantaflow domain's box (its cache-to-world frame, whose unit is the world's): the liquid is clipped to it,
// so liquid pressed against the domain's walls ends in the flat face Mantaflow's mesh closes it with. The
// programs are compiled with and without the clip (CLIP_TO_DOMAIN): llvmpipe would run its code on every
// fragment, and only the ellipsoids that reach the box need it (EllipsoidImpostorPass).
#ifdef CLIP_TO_DOMAIN
const bool clipToDomain = true;
#else
const bool clipToDomain = false;
#endif
uniform mat4 domainFromWorld;
uniform mat4 domainFromCamera;  // domainFromWorld x the view's worldFromCamera, once per draw
uniform vec3 domainLow;
uniform vec3 domainHigh;

// Maps camera-space offsets from an ellipsoid's centre to its unit sphere: x_camera = R x_world + t, so the
// camera-space inverse is the world inverse followed by R^T.
mat3 inverseAxesInCamera(Ellipsoid ellipsoid) {
  mat3 inverseAxesWorld = transpose(mat3(ellipsoid.inverseAxesRows[0].xyz, ellipsoid.inverseAxesRows[1].xyz,
                                         ellipsoid.inverseAxesRows[2].xyz));
  return inverseAxesWorld * transpose(mat3(frame.cameraFromWorld));
}

// The camera in the ellipsoid's unit-sphere space, -A^-1 c: every pixel's ray starts there.
vec3 cameraInUnitSphere(mat3 inverseAxesCamera, vec3 cameraCentre) {
  return -(inverseAxesCamera * cameraCentre);
}

// Whether the last castEllipsoid's surface is the domain box's face (set by castEllipsoid).
bool castOnDomainFace = false;

// Where the ray through a pixel meets the ellipsoid: the eye depth of the surface the layer keeps (the
// nearest front-facing one, or with backFaces the farthest back-facing one), the eye depth where the ray
// enters (which the background test needs) and the world outward normal there; false where the pixel has no
// such surface.
bool castEllipsoid(vec2 fragCoord, vec3 origin, mat3 inverseAxesCamera, out float eyeDepth,
                   out float nearDepth, out vec3 worldNormal) {
  eyeDepth = 0.0;
  nearDepth = 0.0;
  worldNormal = vec3(0.0);
  vec3 direction = normalize(cameraRayFromFragCoord(fragCoord));
  // In the ellipsoid's unit-sphere space the ray is o + t d. Solving around the closest approach
  // t0 = -(o.d)/(d.d) keeps the discriminant accurate thousands of radii away, where the textbook b^2 - ac
  // cancels catastrophically.
  vec3 unitDirection = inverseAxesCamera * direction;
  float a = dot(unitDirection, unitDirection);
  float closest = -dot(origin, unitDirection) / a;
  vec3 closestPoint = origin + closest * unitDirection;
  float halfChordSquared = (1.0 - dot(closestPoint, closestPoint)) / a;
  if (halfChordSquared < 0.0) return false;
  float halfChord = sqrt(halfChordSquared);
  float nearT = closest - halfChord;
  float farT = closest + halfChord;
  if (farT <= 0.0) return false;  // The ellipsoid lies behind the camera.
  // A camera inside the ellipsoid (the camera under water) sees only its back surface.
  bool cameraInside = nearT <= 0.0;
  if (cameraInside && !backFaces) return false;

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
    if (!(clippedNear < clippedFar)) return false;
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
    if (farT <= 0.0 || (nearT <= 0.0 && !backFaces)) return false;
    cameraInside = nearT <= 0.0;
  }
  float t = backFaces ? farT : nearT;
  castOnDomainFace = onBox;

  nearDepth = cameraInside ? getNearClip() : nearT * -direction.z;
  if (nearDepth < getNearClip()) return false;
  eyeDepth = t * -direction.z;
  if (eyeDepth > getFarClip() || eyeDepth < getNearClip()) return false;

  // The gradient of |A^-1 x|^2 is A^-T A^-1 x: the outward normal.
  vec3 unitPoint = origin + t * unitDirection;
  vec3 cameraNormal = normalize(transpose(inverseAxesCamera) * unitPoint);
  // The box frame is a rotation of the world's (unit scale), so its normals turn into the world's by the
  // transpose of its rotation.
  worldNormal = normalize(onBox ? transpose(mat3(domainFromWorld)) * boxNormal
                                : mat3(frame.worldFromCamera) * cameraNormal);
  return true;
}
