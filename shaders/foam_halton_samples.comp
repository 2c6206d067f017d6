#version 450 core
// The foam SSAO's sample set (paper 2.4.1): Halton points in [-1, 1]^3 with their lengths; FoamOcclusionPass
// makes it once. Points with length above 1 lie outside the sphere and are skipped where they are used.
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
