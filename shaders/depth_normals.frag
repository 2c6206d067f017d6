#version 450 core
// Outward world normals of a smoothed depth layer. Per pixel, the camera-space positions of the neighbours
// give one-sided differences along x and y; of each pair the one with the smaller depth step is used, so a
// pixel on a silhouette takes its tangent from its own surface, not from across the depth jump.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"

layout(binding = 0) uniform sampler2D smoothedEyeDepth;
layout(binding = 1) uniform sampler2D originalNormal;  // world normals before smoothing, coverage in w

uniform bool backLayer;  // the layer's outward normals face away from the camera

layout(location = 0) out vec4 outNormal;  // xyz: world normal, w: coverage

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float centreDepth = texelFetch(smoothedEyeDepth, pixel, 0).r;
  outNormal = vec4(0.0);
  if (!hasSurface(centreDepth)) return;

  vec3 towardsSurface = cameraRayFromFragCoord(gl_FragCoord.xy);
  vec3 alongX, alongY;
  vec3 normal = vec3(0.0);
  if (smallerOneSidedDifference(smoothedEyeDepth, pixel, ivec2(1, 0), centreDepth, alongX) &&
      smallerOneSidedDifference(smoothedEyeDepth, pixel, ivec2(0, 1), centreDepth, alongY))
    normal = cross(alongX, alongY);
  float normalLength = length(normal);
  if (normalLength > 0.0 && !isinf(normalLength)) {
    normal /= normalLength;
  } else {
    // A pixel without neighbours along an axis (a one-pixel line or speck) has no tangent plane in the depth
    // map: it keeps its original normal, or faces the camera if that is unusable too.
    vec3 original = mat3(frame.cameraFromWorld) * texelFetch(originalNormal, pixel, 0).xyz;
    float originalLength = length(original);
    normal = originalLength > 0.0 && !isinf(originalLength) ? original / originalLength : -normalize(towardsSurface);
  }
  // Front layers face the camera, back layers face away.
  bool facesAway = dot(normal, towardsSurface) > 0.0;
  if (facesAway != backLayer) normal = -normal;
  outNormal = vec4(normalize(mat3(frame.worldFromCamera) * normal), 1.0);
}
