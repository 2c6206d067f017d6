#pragma once

#include "framedata/RaymarchGridData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "prep/RaymarchPreparation.h"

namespace spindrift {

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
