#version 450 core
// Rim normals, first pass: for each pixel, the signed horizontal offset to the nearest pixel of its row, within
// kRimReach, that the front layer does not cover (0 on such a pixel; kNoEdge where there is none).
// rim_normals.frag finds the nearest uncovered pixel in two dimensions from these rows, a separable search of
// 2 x 17 fetches a pixel rather than 17 x 17. The image's border is not a silhouette: past it the layer is read
// as its border pixel (the texture clamps), so a body cut by the frame's edge is not taken for one ending there.
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"
#include "lib/rim.glsl"

layout(binding = 0) uniform sampler2D frontEyeDepth;

layout(location = 0) out float outOffset;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float nearest = kNoEdge;
  for (int dx = -kRimReach; dx <= kRimReach; ++dx)
    if (abs(float(dx)) < abs(nearest) && !hasSurface(texelAt(frontEyeDepth, pixel + ivec2(dx, 0)).r))
      nearest = float(dx);
  outOffset = nearest;
}
