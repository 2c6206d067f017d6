#version 450 core
// The back layer of a one-draw depth range (ellipsoid_impostor.frag, DEPTH_RANGE): the farthest exit kept by
// GL_MAX blending over a clear of 0, made kNoSurfaceDepth where no ellipsoid was drawn (the front layer's
// clear, kept by GL_MIN blending), as every depth layer marks an empty pixel.
#include "lib/frame.glsl"

layout(binding = 0) uniform sampler2D nearestEntry;
layout(binding = 1) uniform sampler2D farthestExit;

layout(location = 0) out float outEyeDepth;

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  float entry = texelFetch(nearestEntry, texel, 0).r;
  outEyeDepth = entry < 0.5 * kNoSurfaceDepth ? texelFetch(farthestExit, texel, 0).r : kNoSurfaceDepth;
}
