// The exact ray cast of one liquid ellipsoid at a pixel, shared by the impostor pass (which keeps the depth
// and the ellipsoid's index) and its normal resolve (which repeats the cast for the winning ellipsoid only).
// Needs lib/frame.glsl.

struct Ellipsoid {
  vec4 centreAndBoundingRadius;  // world centre, radius of a containing sphere
  vec4 inverseAxesRows[3];       // rows of the world-space inverse axes matrix
  // The window rectangles outside which it cannot hold the front layer (x, y) and the back layer (z, w), each
  // axis (low | high << 16); all bits set where nothing limits it (EllipsoidInstance::shownRectangles).
  uvec4 shownRectangles;
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
uniform vec3 domainLow;
uniform vec3 domainHigh;
// The pixels' rays in the box's frame, as PixelRays (EllipsoidImpostorPass.cpp computes them from the view).
uniform vec3 domainRayAtOrigin;
uniform vec3 domainRayPerPixelX;
uniform vec3 domainRayPerPixelY;
uniform vec3 domainCamera;  // the camera's position in the box's frame

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

// A linear map of the pixels' rays r = (u, v, -1) (cameraRayFromFragCoord, whose parameter is the planar eye
// depth): r is affine in the window position, and so is its image, M r = M r(0, 0) + x M dr/dx + y M dr/dy.
// Per pixel that is two multiply-adds per component where M r was a matrix product of a normalised ray: on
// llvmpipe the ray cast is most of the impostor pass (the dam break's aggregate layers took 21-25 ms with a
// fragment shader that wrote constants, 60-64 with the cast, 51-55 with these rays; docs/frame-cost.md).
struct PixelRays {
  vec3 atOrigin, perPixelX, perPixelY;
};

PixelRays pixelRays(mat3 linear) {
  vec2 perPixel = 2.0 * frame.tanHalfFov.xy * frame.viewportSize.zw;
  return PixelRays(linear * vec3(-frame.tanHalfFov.xy, -1.0), linear * vec3(perPixel.x, 0.0, 0.0),
                   linear * vec3(0.0, perPixel.y, 0.0));
}

vec3 pixelRay(PixelRays rays, vec2 fragCoord) {
  return rays.atOrigin + fragCoord.x * rays.perPixelX + fragCoord.y * rays.perPixelY;
}

// Where one pixel's ray meets an ellipsoid (castEllipsoid).
struct EllipsoidCast {
  float eyeDepth;   // of the surface the layer keeps
  float nearDepth;  // where the ray enters (the background test needs it)
  vec3 unitPoint;   // that surface in the unit-sphere space
  bool onDomainFace;
  vec3 domainFaceNormal;  // in the box's frame, where onDomainFace
};

// Where the ray through a pixel meets the ellipsoid whose unit-sphere space holds the camera at `origin` and
// the pixels' rays `rays`: the surface the layer keeps (the nearest front-facing one, or with backFaces the
// farthest back-facing one) and where the ray enters; false where the pixel has no such surface. The
// impostor pass and its normal resolve call it with the same arithmetic, so that they agree on every pixel.
bool castEllipsoid(vec2 fragCoord, vec3 origin, PixelRays rays, out EllipsoidCast surface) {
  surface = EllipsoidCast(0.0, 0.0, vec3(0.0), false, vec3(0.0));
  // In the ellipsoid's unit-sphere space the ray is o + t d, t the eye depth. Solving around the closest
  // approach t0 = -(o.d)/(d.d) keeps the discriminant accurate thousands of radii away, where the textbook
  // b^2 - ac cancels catastrophically.
  vec3 unitDirection = pixelRay(rays, fragCoord);
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

  // Clip the chord [nearT, farT] to the domain's box (slab test in the box's frame, where the same ray has
  // the same parameter); where the box cuts the ellipsoid the surface is the box's face, with its normal.
  if (clipToDomain) {
    vec3 boxDirection = domainRayAtOrigin + fragCoord.x * domainRayPerPixelX + fragCoord.y * domainRayPerPixelY;
    vec3 inverse = 1.0 / boxDirection;
    vec3 tLow = (domainLow - domainCamera) * inverse, tHigh = (domainHigh - domainCamera) * inverse;
    vec3 tEnter = min(tLow, tHigh), tLeave = max(tLow, tHigh);
    float enter = max(tEnter.x, max(tEnter.y, tEnter.z)), leave = min(tLeave.x, min(tLeave.y, tLeave.z));
    float clippedNear = max(nearT, enter), clippedFar = min(farT, leave);
    if (!(clippedNear < clippedFar)) return false;
    if (!backFaces && enter > nearT) {
      int axis = enter == tEnter.x ? 0 : (enter == tEnter.y ? 1 : 2);
      surface.domainFaceNormal[axis] = -sign(boxDirection[axis]);
      surface.onDomainFace = true;
    } else if (backFaces && leave < farT) {
      int axis = leave == tLeave.x ? 0 : (leave == tLeave.y ? 1 : 2);
      surface.domainFaceNormal[axis] = sign(boxDirection[axis]);
      surface.onDomainFace = true;
    }
    nearT = clippedNear;
    farT = clippedFar;
    if (farT <= 0.0 || (nearT <= 0.0 && !backFaces)) return false;
    cameraInside = nearT <= 0.0;
  }
  float t = backFaces ? farT : nearT;
  surface.nearDepth = cameraInside ? getNearClip() : nearT;
  if (surface.nearDepth < getNearClip()) return false;
  surface.eyeDepth = t;
  if (t > getFarClip() || t < getNearClip()) return false;
  surface.unitPoint = origin + t * unitDirection;
  return true;
}

// The world outward normal of a cast surface: the box's face, or the gradient of |A^-1 x|^2, A^-T A^-1 x.
vec3 castWorldNormal(EllipsoidCast surface, mat3 inverseAxesCamera) {
  // The box frame is a rotation of the world's (unit scale), so its normals turn into the world's by the
  // transpose of its rotation.
  if (surface.onDomainFace) return normalize(transpose(mat3(domainFromWorld)) * surface.domainFaceNormal);
  return normalize(mat3(frame.worldFromCamera) * normalize(transpose(inverseAxesCamera) * surface.unitPoint));
}
