#version 450 core
// Draws each liquid particle's ellipsoid as one triangle around its projection: the equilateral triangle that
// circumscribes the unit circle, mapped onto the ellipse that the ellipsoid's silhouette is (its dual conic, as
// Sigg et al. 2006, section 3.2, derive its axis-aligned box). Where that ellipse does not exist (an ellipsoid
// reaching the camera plane) the triangle circumscribes its bounding sphere's silhouette instead. The fragment
// shader ray-casts the exact ellipsoid (lib/ellipsoid_ray.glsl). On llvmpipe a particle costs the triangles
// set up for it and the fragments they cover: one triangle of 1.3 times the area of the rectangle along the
// ellipse's axes (two triangles) drew the dam break's aggregate layers in 60-63 ms instead of 61-70, the
// layers bit-identical (docs/frame-cost.md). Three vertices per particle (gl_VertexID / 3 names it), drawn as
// arrays rather than one instance each: llvmpipe pays per instance.
#include "lib/around_unit_circle.glsl"
#include "lib/frame.glsl"
#include "lib/ellipsoid_ray.glsl"

uniform int firstEllipsoid;  // This layer draws ellipsoids [firstEllipsoid, firstEllipsoid + count).

// The camera in the ellipsoid's unit-sphere space, -A^-1 c: every fragment's ray starts there.
flat out vec3 vUnitSphereCamera;
// The pixels' rays in the unit-sphere space (PixelRays of A^-1 in camera space).
flat out vec3 vUnitRayAtOrigin;
flat out vec3 vUnitRayPerPixelX;
flat out vec3 vUnitRayPerPixelY;
flat out uint vEllipsoid;  // its index in the list

const float kSilhouetteMarginPixels = 0.1;
const uint kShownEverywhere = 0xffffffffu;

// Widens [low, high] by one layer's shown rectangle (EllipsoidInstance::shownRectangles); false where that
// layer's rectangle does not limit the ellipsoid. A rectangle whose low exceeds its high is empty.
bool widenByShown(uvec2 bits, inout vec2 low, inout vec2 high) {
  if (bits.x == kShownEverywhere) return false;
  vec2 layerLow = vec2(bits & 0xffffu), layerHigh = vec2(bits >> 16);
  if (all(lessThanEqual(layerLow, layerHigh))) {
    low = min(low, layerLow);
    high = max(high, layerHigh);
  }
  return true;
}

// The window rectangle of pixels (inclusive) this draw must shade of the ellipsoid: where it may hold the
// layer's surface (the occlusion test's, prep/OccludedAggregates.cpp), both layers' with DEPTH_RANGE; false
// where nothing limits it.
bool shownRectangle(Ellipsoid ellipsoid, out vec2 low, out vec2 high) {
  low = vec2(1e9);
  high = vec2(-1e9);
#ifdef DEPTH_RANGE
  return widenByShown(ellipsoid.shownRectangles.xy, low, high) &&
         widenByShown(ellipsoid.shownRectangles.zw, low, high);
#else
  return widenByShown(backFaces ? ellipsoid.shownRectangles.zw : ellipsoid.shownRectangles.xy, low, high);
#endif
}

void main() {
  vEllipsoid = uint(firstEllipsoid + gl_VertexID / 3);
  vec2 corner = kAroundUnitCircle[gl_VertexID % 3];
  Ellipsoid ellipsoid = ellipsoids[vEllipsoid];
  vec3 centre = (frame.cameraFromWorld * vec4(ellipsoid.centreAndBoundingRadius.xyz, 1.0)).xyz;
  float radius = ellipsoid.centreAndBoundingRadius.w;
  // The normal resolve (ellipsoid_normals.frag) derives these with the same functions.
  mat3 inverseAxesCamera = inverseAxesInCamera(ellipsoid);
  vUnitSphereCamera = cameraInUnitSphere(inverseAxesCamera, centre);
  PixelRays unitRays = pixelRays(inverseAxesCamera);
  vUnitRayAtOrigin = unitRays.atOrigin;
  vUnitRayPerPixelX = unitRays.perPixelX;
  vUnitRayPerPixelY = unitRays.perPixelY;

  // Tight bounds: the unit sphere maps to clip space by T = clipFromCamera [A c; 0 1], and the ellipsoid's
  // dual quadric there is Q* = T D T^T with D = diag(1, 1, 1, -1), whose entries are the rows r of T paired
  // by D. Its silhouette's dual conic is Q*'s x, y, w rows and columns; an ellipse of centre m and shape S
  // ({m + S^1/2 u : |u| <= 1}) has the dual conic [m m^T - S, m; m^T, 1] up to scale, so dividing by wDw
  // gives both. It holds while the whole ellipsoid is in front of the camera plane, that is wDw < 0.
  mat4 axes = mat4(inverse(inverseAxesCamera));
  axes[3] = vec4(centre, 1.0);
  mat4 rows = transpose(frame.clipFromCamera * axes);
  const vec4 signs = vec4(1.0, 1.0, 1.0, -1.0);
  float wDw = dot(rows[3], signs * rows[3]);
  vec2 middle = vec2(dot(rows[0], signs * rows[3]), dot(rows[1], signs * rows[3])) / wDw;
  // The shape in pixels (NDC spans two units of the viewport's width and height).
  vec2 pixelsPerUnit = 0.5 * frame.viewportSize.xy;
  float xx = middle.x * middle.x - dot(rows[0], signs * rows[0]) / wDw;
  float yy = middle.y * middle.y - dot(rows[1], signs * rows[1]) / wDw;
  float xy = middle.x * middle.y - dot(rows[0], signs * rows[1]) / wDw;
  mat2 shape = mat2(xx * pixelsPerUnit.x * pixelsPerUnit.x, xy * pixelsPerUnit.x * pixelsPerUnit.y,
                    xy * pixelsPerUnit.x * pixelsPerUnit.y, yy * pixelsPerUnit.y * pixelsPerUnit.y);
  if (wDw < 0.0 && shape[0][0] >= 0.0 && shape[1][1] >= 0.0) {
    // The triangle along the ellipse's own axes (the eigenvectors of its shape): a thin ellipse seen slanted
    // fills a small part of its axis-aligned box.
    float mean = 0.5 * (shape[0][0] + shape[1][1]);
    float spread = length(vec2(0.5 * (shape[0][0] - shape[1][1]), shape[0][1]));
    vec2 halfAxes = sqrt(max(vec2(mean + spread, mean - spread), 0.0));
    vec2 major = shape[0][0] >= shape[1][1] ? vec2(spread + 0.5 * (shape[0][0] - shape[1][1]), shape[0][1])
                                            : vec2(shape[0][1], spread - 0.5 * (shape[0][0] - shape[1][1]));
    major = dot(major, major) > 0.0 ? normalize(major) : vec2(1.0, 0.0);
    // A tenth of a pixel of margin keeps every pixel centre the exact silhouette covers inside, despite
    // rounding (the images were bit-identical to those of the axis-aligned box with a whole pixel's margin).
    halfAxes += kSilhouetteMarginPixels;
    vec2 offset = corner.x * halfAxes.x * major + corner.y * halfAxes.y * vec2(-major.y, major.x);
    // The rectangle's depth is irrelevant (the fragment shader writes gl_FragDepth); mid-range keeps it
    // inside the clip volume.
    float bound = backFaces ? -centre.z + radius : -centre.z - radius;
    float depth = depthBufferFromEyeDepth(bound) * 2.0 - 1.0;
    gl_Position = vec4(middle + offset / pixelsPerUnit, depth, 1.0);
    // Where the occlusion test limits it to a smaller rectangle, the right triangle whose legs are twice the
    // rectangle's sides (its hypotenuse through the far corner; pixel centres lie half a pixel inside) instead:
    // llvmpipe pays for every fragment the triangle covers, and the fragments outside the ellipse discard.
    vec2 low, high;
    if (shownRectangle(ellipsoid, low, high)) {
      vec2 size = max(high + 1.0 - low, vec2(0.0));
      if (2.0 * size.x * size.y < 5.196152 * halfAxes.x * halfAxes.y) {  // the ellipse's triangle: 3 sqrt 3 ab
        vec2 window = low + 2.0 * size * vec2(gl_VertexID % 3 == 1, gl_VertexID % 3 == 2);
        gl_Position = vec4(window / pixelsPerUnit - 1.0, depth, 1.0);
      }
    }
    return;
  }

  float distanceToCentre = length(centre);
  if (distanceToCentre <= radius * 1.0001) {
    // A camera inside the liquid sits inside a few particles. Their back surfaces are what it sees above it
    // (the liquid's surface from below), so the back layer draws them over the whole screen and the fragment
    // shader ray-casts each pixel; the front layer has no use for them. Twice the triangle around the unit
    // circle holds every point within 2 of the centre, the clip square [-1, 1]^2 among them.
    gl_Position = backFaces ? vec4(2.0 * corner, 0.0, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  // Spheres behind the camera are culled; this also guards the square root below.
  if (centre.z >= 0.0) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  vec3 direction = centre / distanceToCentre;
  vec3 helper = abs(direction.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 right = normalize(cross(helper, direction));
  vec3 up = cross(direction, right);
  // The triangle lies in the plane perpendicular to the view direction through the bounding sphere's nearest
  // point, kept in front of the near plane. The silhouette cone has half-angle asin(r / d), so at distance D
  // its circle has radius D r / sqrt(d^2 - r^2); the triangle around it gets a 1% margin.
  float planeDistance = max(distanceToCentre - radius, 1.01 * getNearClip() / max(-direction.z, 1e-3));
  float halfSize = planeDistance * radius / sqrt((distanceToCentre - radius) * (distanceToCentre + radius));
  vec3 position = direction * planeDistance + (right * corner.x + up * corner.y) * halfSize * 1.01;
  gl_Position = frame.clipFromCamera * vec4(position, 1.0);
}
