#version 450 core
// The occluder depth prepass (OccluderDepthPass): world-space triangles to the frame's camera. Planar eye
// depth is affine in world space, so the rasteriser's perspective-correct interpolation gives it exactly.
#include "lib/frame.glsl"

layout(location = 0) in vec3 worldPosition;

out float eyeDepth;

void main() {
  vec4 cameraPosition = frame.cameraFromWorld * vec4(worldPosition, 1.0);
  eyeDepth = -cameraPosition.z;
  gl_Position = frame.clipFromCamera * cameraPosition;
}
