#version 450 core
// The normal resolve of the impostor pass: where a layer holds a surface, the ray cast of the ellipsoid that
// won the pixel (ellipsoid_impostor.frag) is repeated to find its world outward normal. Output as the depth
// layers keep it: xyz the normal, w the coverage (1, or 0 where the layer is empty).
#include "lib/frame.glsl"
#include "lib/ellipsoid_ray.glsl"

layout(binding = 0) uniform usampler2D winningEllipsoid;  // index + 1, 0 where empty

layout(location = 0) out vec4 outNormal;

void main() {
  outNormal = vec4(0.0);
  uint winner = texelFetch(winningEllipsoid, ivec2(gl_FragCoord.xy), 0).r;
  if (winner == 0u) return;
  Ellipsoid ellipsoid = ellipsoids[winner - 1u];
  vec3 centre = (frame.cameraFromWorld * vec4(ellipsoid.centreAndBoundingRadius.xyz, 1.0)).xyz;
  mat3 inverseAxes = inverseAxesInCamera(ellipsoid);
  EllipsoidCast surface;
  // The cast succeeded when the impostor pass drew this pixel; it is repeated with the same arithmetic.
  if (castEllipsoid(gl_FragCoord.xy, cameraInUnitSphere(inverseAxes, centre), pixelRays(inverseAxes), surface))
    outNormal = vec4(castWorldNormal(surface, inverseAxes), 1.0);
}
