#version 450 core
// The GPU neighbour grid of the ray-marched surface, built in five stages (one dispatch each): count the
// particles per cell (remembering each particle's slot in its cell), sum blocks of cells, scan the block sums,
// write each cell's first index, and scatter the particles into cell order.
layout(local_size_x = 64) in;
#include "lib/raymarch_grid.glsl"

layout(std430, binding = 0) readonly buffer Particles { vec4 particles[]; };
layout(std430, binding = 3) buffer ParticleSlots { uvec2 particleSlot[]; };  // cell, slot in the cell
layout(std430, binding = 5) buffer BlockSums { uint blockSum[]; };

uniform int stage;
uniform uint particleCount;
uniform uint totalCells;
uniform uint blockCount;
const uint kBlockCells = 1024u;

void main() {
  uint id = gl_GlobalInvocationID.x;
  if (stage == 0) {
    if (id >= particleCount) return;
    ivec3 cell = clamp(cellOf(particles[id].xyz), ivec3(0), gridSize - 1);
    uint index = uint(cellIndex(cell));
    particleSlot[id] = uvec2(index, atomicAdd(cellCount[index], 1u));
  } else if (stage == 1) {
    if (id >= blockCount) return;
    uint sum = 0u;
    uint end = min(totalCells, (id + 1u) * kBlockCells);
    for (uint c = id * kBlockCells; c < end; ++c) sum += cellCount[c];
    blockSum[id] = sum;
  } else if (stage == 2) {
    if (id != 0u) return;
    uint running = 0u;
    for (uint b = 0u; b < blockCount; ++b) {
      uint sum = blockSum[b];
      blockSum[b] = running;
      running += sum;
    }
  } else if (stage == 3) {
    if (id >= blockCount) return;
    uint running = blockSum[id];
    uint end = min(totalCells, (id + 1u) * kBlockCells);
    for (uint c = id * kBlockCells; c < end; ++c) {
      cellStart[c] = running;
      running += cellCount[c];
    }
  } else {
    if (id >= particleCount) return;
    uvec2 slot = particleSlot[id];
    sortedParticles[cellStart[slot.x] + slot.y] = particles[id];
  }
}
