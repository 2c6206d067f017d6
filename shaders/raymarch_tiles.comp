#version 450 core
// Adaptive ray casting resolution (adaptive ray marching paper, 4.3): per screen tile the variance of D_all
// picks the spacing of the rays cast in it. Var > epsilon_2: every pixel (level 0); epsilon_1 < Var <=
// epsilon_2: every second pixel in x and y (level 1); Var <= epsilon_1: every fourth (level 2). Two choices
// of ours (docs/raymarch.md): the variance is taken about the tile's least-squares plane of depth over the
// pixel position, so flat water seen at a slant counts as flat (for a surface facing the camera it is the
// plain variance); and a tile where liquid meets background holds a silhouette, which interpolation would
// blur, so it is cast at full resolution. A tile without liquid casts no rays (level 3).
layout(local_size_x = 16, local_size_y = 16) in;
#include "lib/frame.glsl"
#include "lib/depth_layer.glsl"

layout(binding = 0) uniform sampler2D allDepth;
layout(binding = 0, r8ui) uniform writeonly uimage2D tileLevels;
layout(std430, binding = 1) buffer TileHistogram { uint tilesAtLevel[4]; };

uniform int tileSize;
uniform float varianceLow;   // epsilon_1, world units squared
uniform float varianceHigh;  // epsilon_2
uniform int forcedLevel;     // -1: adaptive; 0, 1 or 2: that level wherever there is liquid

const int kSums = 6;
shared float partial[kSums][256];

// Sums partial[k][*] over the work group into partial[k][0].
void reduce(uint thread) {
  for (uint stride = 128u; stride > 0u; stride >>= 1u) {
    barrier();
    if (thread < stride)
      for (int k = 0; k < kSums; ++k) partial[k][thread] += partial[k][thread + stride];
  }
  barrier();
}

void main() {
  ivec2 tile = ivec2(gl_WorkGroupID.xy);
  uint thread = gl_LocalInvocationIndex;
  ivec2 first = tile * tileSize;
  ivec2 last = min(first + tileSize, ivec2(frame.viewportSize.xy));
  // First pass: counts and means; second: centred second moments (stable in float).
  float sums[kSums] = float[kSums](0.0, 0.0, 0.0, 0.0, 0.0, 0.0);  // surface pixels, empty pixels, x, y, z
  for (int y = first.y + int(gl_LocalInvocationID.y); y < last.y; y += 16)
    for (int x = first.x + int(gl_LocalInvocationID.x); x < last.x; x += 16) {
      float depth = texelFetch(allDepth, ivec2(x, y), 0).r;
      if (hasSurface(depth)) {
        sums[0] += 1.0;
        sums[2] += float(x - first.x);
        sums[3] += float(y - first.y);
        sums[4] += depth;
      } else {
        sums[1] += 1.0;
      }
    }
  for (int k = 0; k < kSums; ++k) partial[k][thread] = sums[k];
  reduce(thread);
  float surfacePixels = partial[0][0], emptyPixels = partial[1][0];
  vec3 mean = surfacePixels > 0.0 ? vec3(partial[2][0], partial[3][0], partial[4][0]) / surfacePixels : vec3(0.0);
  barrier();
  float moments[kSums] = float[kSums](0.0, 0.0, 0.0, 0.0, 0.0, 0.0);  // xx, xy, yy, xz, yz, zz
  for (int y = first.y + int(gl_LocalInvocationID.y); y < last.y; y += 16)
    for (int x = first.x + int(gl_LocalInvocationID.x); x < last.x; x += 16) {
      float depth = texelFetch(allDepth, ivec2(x, y), 0).r;
      if (!hasSurface(depth)) continue;
      vec3 d = vec3(float(x - first.x), float(y - first.y), depth) - mean;
      moments[0] += d.x * d.x;
      moments[1] += d.x * d.y;
      moments[2] += d.y * d.y;
      moments[3] += d.x * d.z;
      moments[4] += d.y * d.z;
      moments[5] += d.z * d.z;
    }
  for (int k = 0; k < kSums; ++k) partial[k][thread] = moments[k];
  reduce(thread);
  if (thread != 0u) return;
  int level;
  if (surfacePixels == 0.0) {
    level = 3;
  } else if (forcedLevel >= 0) {
    level = forcedLevel;
  } else if (emptyPixels > 0.0) {
    level = 0;
  } else {
    // Least squares z = mean.z + s (x - mean.x) + t (y - mean.y); the residual variance is what the plane
    // leaves: (zz - s xz - t yz) / n.
    float xx = partial[0][0], xy = partial[1][0], yy = partial[2][0];
    float xz = partial[3][0], yz = partial[4][0], zz = partial[5][0];
    float determinant = xx * yy - xy * xy;
    float explained = 0.0;
    if (determinant > 1e-6 * (xx * yy + 1e-12)) {
      float s = (xz * yy - yz * xy) / determinant, t = (yz * xx - xz * xy) / determinant;
      explained = s * xz + t * yz;
    }
    float variance = max(zz - explained, 0.0) / surfacePixels;
    level = variance > varianceHigh ? 0 : (variance > varianceLow ? 1 : 2);
  }
  imageStore(tileLevels, tile, uvec4(uint(level)));
  atomicAdd(tilesAtLevel[level], 1u);
}
