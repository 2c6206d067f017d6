#version 450 core
// The irradiance map of the foam's fast path (paper 2.4.2, last sentence): per texel direction n, the
// cosine-weighted mean (1 / 2 pi) * integral of L(w) max(0, w . n) dw over the environment, taken on a
// 64 x 32 grid of directions weighted by their solid angle. A uniform environment L gives L / 2, as the
// sampled estimate does.
#include "lib/environment.glsl"
#include "lib/foam_environment.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba16f) uniform writeonly image2D irradianceMap;

const int kAzimuthSteps = 64;
const int kElevationSteps = 32;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(irradianceMap);
  if (any(greaterThanEqual(texel, size))) return;
  vec3 normal = directionFromEquirectangularUv((vec2(texel) + 0.5) / vec2(size));
  vec3 sum = vec3(0.0);
  for (int j = 0; j < kElevationSteps; ++j) {
    float v = (float(j) + 0.5) / float(kElevationSteps);
    float cellSolidAngle = (2.0 * kPi / float(kAzimuthSteps)) * (kPi / float(kElevationSteps)) * cos((v - 0.5) * kPi);
    for (int i = 0; i < kAzimuthSteps; ++i) {
      vec3 direction = directionFromEquirectangularUv(vec2((float(i) + 0.5) / float(kAzimuthSteps), v));
      sum += environmentRadiance(direction) * max(dot(direction, normal), 0.0) * cellSolidAngle;
    }
  }
  imageStore(irradianceMap, texel, vec4(sum / (2.0 * kPi), 1.0));
}
