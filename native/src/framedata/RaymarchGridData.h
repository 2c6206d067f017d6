#pragma once

#include "gl/GlObjects.h"
#include "prep/RaymarchPreparation.h"

namespace spindrift {

/// The GPU neighbour grid of the ray-marched surface (RaymarchGridPass's output): per cell its particle count
/// and first index into the particles sorted by cell, as shaders/lib/raymarch_grid.glsl reads them.
struct RaymarchGridData {
  const BufferObject& cellCounts;       ///< uint per cell (binding 1)
  const BufferObject& cellStarts;       ///< uint per cell (binding 2)
  const BufferObject& sortedParticles;  ///< vec4 per particle, xyz position (binding 4)
  RaymarchGrid grid;
  float smoothingRadius;
};

/// Binds the grid's buffers and sets the grid uniforms of lib/raymarch_grid.glsl on a current program
/// (defined in RaymarchGridPass.cpp).
void bindRaymarchGrid(GLuint program, const RaymarchGridData& grid);

}  // namespace spindrift
