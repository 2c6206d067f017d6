// The background's world normal at a pixel, rebuilt from its eye depth. Requires lib/frame.glsl and
// lib/depth_layer.glsl.

// The smaller one-sided differences, as the liquid's depth normals take them, facing the camera; zero where a
// neighbour is missing along an axis (a lone pixel, the edge of a solid against the sky).
// In camera space.
vec3 backgroundCameraNormal(sampler2D eyeDepthTexture, ivec2 pixel, float eyeDepth) {
  vec3 alongX, alongY;
  if (!smallerOneSidedDifference(eyeDepthTexture, pixel, ivec2(1, 0), eyeDepth, alongX) ||
      !smallerOneSidedDifference(eyeDepthTexture, pixel, ivec2(0, 1), eyeDepth, alongY))
    return vec3(0.0);
  vec3 normal = cross(alongX, alongY);
  if (!(dot(normal, normal) > 0.0)) return vec3(0.0);
  normal = normalize(normal);
  return dot(normal, cameraRayFromFragCoord(vec2(pixel) + 0.5)) > 0.0 ? -normal : normal;
}

vec3 backgroundNormal(sampler2D eyeDepthTexture, ivec2 pixel, float eyeDepth) {
  return mat3(frame.worldFromCamera) * backgroundCameraNormal(eyeDepthTexture, pixel, eyeDepth);
}
