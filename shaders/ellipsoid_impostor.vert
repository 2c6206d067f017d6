#version 450 core
// Draws each liquid particle's ellipsoid as a screen rectangle that bounds its exact projection (Sigg et al.
// 2006, section 3.2), or, where that does not exist (an ellipsoid reaching the camera plane), as a
// camera-facing quad around its bounding sphere's silhouette; the fragment shader ray-casts the exact
// ellipsoid (lib/ellipsoid_ray.glsl). A flattened ellipsoid seen edge-on covers a fraction of its bounding
// sphere's square, and every fragment of the quad costs a ray cast. Four vertices per particle (gl_VertexID
// / 4 names it), drawn as two indexed triangles rather than one instance each: llvmpipe pays per instance,
// and the lights' views of a thick body drew 1.8 times faster so (docs/frame-cost.md).
#include "lib/frame.glsl"
#include "lib/ellipsoid_ray.glsl"

uniform int firstEllipsoid;  // This layer draws ellipsoids [firstEllipsoid, firstEllipsoid + count).

// The camera in the ellipsoid's unit-sphere space, -A^-1 c: every fragment's ray starts there.
flat out vec3 vUnitSphereCamera;
flat out mat3 vInverseAxesCamera;  // maps camera-space offsets from the centre to the unit sphere
flat out uint vEllipsoid;          // its index in the list

void main() {
  vEllipsoid = uint(firstEllipsoid + (gl_VertexID >> 2));
  Ellipsoid ellipsoid = ellipsoids[vEllipsoid];
  vec3 centre = (frame.cameraFromWorld * vec4(ellipsoid.centreAndBoundingRadius.xyz, 1.0)).xyz;
  float radius = ellipsoid.centreAndBoundingRadius.w;
  // The normal resolve (ellipsoid_normals.frag) derives both with the same functions.
  vInverseAxesCamera = inverseAxesInCamera(ellipsoid);
  vUnitSphereCamera = cameraInUnitSphere(vInverseAxesCamera, centre);

  // Tight bounds: the unit sphere maps to clip space by T = clipFromCamera [A c; 0 1]. A clip-space plane
  // x - s w = 0 touches the ellipsoid where (r1 - s r4) D (r1 - s r4) = 0 with D = diag(1, 1, 1, -1) and r
  // the rows of T: a quadratic in s whose roots are the rectangle's sides (likewise y with r2). It holds while
  // the whole ellipsoid is in front of the camera plane, that is r4 D r4 < 0.
  mat3 axes = inverse(vInverseAxesCamera);
  mat4 clipFromUnitSphere = frame.clipFromCamera * mat4(vec4(axes[0], 0.0), vec4(axes[1], 0.0),
                                                        vec4(axes[2], 0.0), vec4(centre, 1.0));
  mat4 rows = transpose(clipFromUnitSphere);
  const vec4 signs = vec4(1.0, 1.0, 1.0, -1.0);
  float wDw = dot(rows[3], signs * rows[3]);
  float xDw = dot(rows[0], signs * rows[3]), xDx = dot(rows[0], signs * rows[0]);
  float yDw = dot(rows[1], signs * rows[3]), yDy = dot(rows[1], signs * rows[1]);
  float xDiscriminant = xDw * xDw - wDw * xDx, yDiscriminant = yDw * yDw - wDw * yDy;
  if (wDw < 0.0 && xDiscriminant >= 0.0 && yDiscriminant >= 0.0) {
    vec2 middle = vec2(xDw, yDw) / wDw;
    vec2 halfExtent = abs(sqrt(vec2(xDiscriminant, yDiscriminant)) / wDw);
    // One pixel of margin keeps every pixel centre the exact silhouette covers inside, despite rounding.
    halfExtent += 2.0 * frame.viewportSize.zw;
    vec2 corner = vec2(gl_VertexID & 1, (gl_VertexID >> 1) & 1) * 2.0 - 1.0;
    // The rectangle's depth is irrelevant (the fragment shader writes gl_FragDepth); mid-range keeps it
    // inside the clip volume.
    float bound = backFaces ? -centre.z + radius : -centre.z - radius;
    gl_Position = vec4(middle + corner * halfExtent, depthBufferFromEyeDepth(bound) * 2.0 - 1.0, 1.0);
    return;
  }

  float distanceToCentre = length(centre);
  vec2 corner = vec2(gl_VertexID & 1, (gl_VertexID >> 1) & 1) * 2.0 - 1.0;
  if (distanceToCentre <= radius * 1.0001) {
    // A camera inside the liquid sits inside a few particles. Their back surfaces are what it sees above it
    // (the liquid's surface from below), so the back layer draws them over the whole screen and the fragment
    // shader ray-casts each pixel; the front layer has no use for them.
    gl_Position = backFaces ? vec4(corner, 0.0, 1.0) : vec4(2.0, 2.0, 2.0, 1.0);
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
  // The quad lies in the plane perpendicular to the view direction through the bounding sphere's nearest
  // point, kept in front of the near plane. The silhouette cone has half-angle asin(r / d), so at distance D
  // its circle has radius D r / sqrt(d^2 - r^2); the square around it gets a 1% margin.
  float planeDistance = max(distanceToCentre - radius, 1.01 * getNearClip() / max(-direction.z, 1e-3));
  float halfSize = planeDistance * radius / sqrt((distanceToCentre - radius) * (distanceToCentre + radius));
  vec3 position = direction * planeDistance + (right * corner.x + up * corner.y) * halfSize * 1.01;
  gl_Position = frame.clipFromCamera * vec4(position, 1.0);
}
