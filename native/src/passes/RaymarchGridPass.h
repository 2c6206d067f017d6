#pragma once

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "prep/RaymarchPreparation.h"

namespace spindrift {

/// The GPU neighbour grid of the ray-marched surface: per cell its particle count and first index into the
/// particles sorted by cell (shaders/lib/raymarch_grid.glsl reads it).
struct RaymarchGridData {
  const BufferObject& cellCounts;       ///< uint per cell (binding 1)
  const BufferObject& cellStarts;       ///< uint per cell (binding 2)
  const BufferObject& sortedParticles;  ///< vec4 per particle, xyz position (binding 4)
  RaymarchGrid grid;
  float smoothingRadius;
};

/// Binds the grid's buffers and sets the grid uniforms of lib/raymarch_grid.glsl on a current program.
void bindRaymarchGrid(GLuint program, const RaymarchGridData& grid);

/// Builds the cell lists on the GPU (shaders/raymarch_grid.comp): count per cell with atomics, a two-level
/// exclusive scan of the counts, then a scatter of the particles into cell order.
class RaymarchGridPass {
 public:
  explicit RaymarchGridPass(const ShaderLibrary& shaders);
  RaymarchGridData run(const RaymarchPreparation& preparation);

 private:
  void ensureCapacity(std::size_t particles, std::size_t cells);

  ProgramObject program_;
  BufferObject particles_, slots_, cellCounts_, cellStarts_, sortedParticles_, blockSums_;
  std::size_t particleCapacity_ = 0;
  std::size_t cellCapacity_ = 0;
};

}  // namespace spindrift
