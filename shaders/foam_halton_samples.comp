#version 450 core
// The foam SSAO's sample set (paper 2.4.1): Halton points in [-1, 1]^3 with their lengths; FoamOcclusionPass
// makes it once and keeps the points inside the unit sphere (length at most 1), which the paper uses.
#include "lib/foam_functions.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) writeonly buffer HaltonSamples {
  vec4 haltonSamples[];
};

void main() {
  uint i = gl_GlobalInvocationID.x;
  vec3 point = haltonCubeSample(i);
  haltonSamples[i] = vec4(point, length(point));
}
