#version 450 core
// The binary density grid M (adaptive ray marching paper, 4.1): the particle counts N convolved with the
// separable kernel K = (b, a, b) x (b, a, b) x (b, a, b) (equation 5, one axis per stage), then
// M_c = [m N_c W(0, h) >= sigma] (equations 1 and 3), which with densities in units of m W(0, h) reads
// N_c >= iso. The last stage packs the 2x2x2 cells of a block into the 8 bits of one texel of the compact mask,
// so one fetch answers for 8 cells and a zero texel lets a ray skip the whole block.
layout(local_size_x = 64) in;
#include "lib/raymarch_grid.glsl"

layout(std430, binding = 6) buffer ConvolvedX { float convolvedX[]; };
layout(std430, binding = 7) buffer ConvolvedXY { float convolvedXY[]; };
layout(binding = 0, r8ui) uniform writeonly uimage3D densityMask;

uniform int stage;
uniform float centreWeight;  // a
uniform float sideWeight;    // b
uniform float iso;

float countAt(ivec3 cell) { return insideGrid(cell) ? float(cellCount[cellIndex(cell)]) : 0.0; }
float convolvedXAt(ivec3 cell) { return insideGrid(cell) ? convolvedX[cellIndex(cell)] : 0.0; }
float convolvedXYAt(ivec3 cell) { return insideGrid(cell) ? convolvedXY[cellIndex(cell)] : 0.0; }

ivec3 cellOfIndex(int index) {
  return ivec3(index % gridSize.x, (index / gridSize.x) % gridSize.y, index / (gridSize.x * gridSize.y));
}

void main() {
  int id = int(gl_GlobalInvocationID.x);
  int cells = gridSize.x * gridSize.y * gridSize.z;
  if (stage == 0) {
    if (id >= cells) return;
    ivec3 c = cellOfIndex(id);
    convolvedX[id] = sideWeight * (countAt(c - ivec3(1, 0, 0)) + countAt(c + ivec3(1, 0, 0))) +
                     centreWeight * countAt(c);
  } else if (stage == 1) {
    if (id >= cells) return;
    ivec3 c = cellOfIndex(id);
    convolvedXY[id] = sideWeight * (convolvedXAt(c - ivec3(0, 1, 0)) + convolvedXAt(c + ivec3(0, 1, 0))) +
                      centreWeight * convolvedXAt(c);
  } else {
    ivec3 blocks = gridSize / 2;
    if (id >= blocks.x * blocks.y * blocks.z) return;
    ivec3 block = ivec3(id % blocks.x, (id / blocks.x) % blocks.y, id / (blocks.x * blocks.y));
    uint bits = 0u;
    for (int bit = 0; bit < 8; ++bit) {
      ivec3 c = block * 2 + ivec3(bit & 1, (bit >> 1) & 1, (bit >> 2) & 1);
      float neighbours = sideWeight * (convolvedXYAt(c - ivec3(0, 0, 1)) + convolvedXYAt(c + ivec3(0, 0, 1))) +
                         centreWeight * convolvedXYAt(c);
      if (neighbours >= iso) bits |= 1u << uint(bit);
    }
    imageStore(densityMask, block, uvec4(bits));
  }
}
