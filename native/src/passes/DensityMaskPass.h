#pragma once

#include <cstdint>
#include <vector>

#include "framedata/DensityMaskData.h"
#include "framedata/RaymarchGridData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// The binary density grid M of the adaptive ray marching paper (4.1), made on the GPU from the neighbour
/// grid's counts (shaders/raymarch_density_mask.comp): separable (b, a, b) convolution, threshold, packing.
class DensityMaskPass {
 public:
  explicit DensityMaskPass(const ShaderLibrary& shaders);
  DensityMaskData run(const RaymarchGridData& grid, const LiquidParameters& parameters);
  /// The mask of the last run unpacked to one byte per cell, x fastest (for the tests; waits for the GPU).
  std::vector<std::uint8_t> readCells() const;

 private:
  ProgramObject program_;
  BufferObject convolvedX_, convolvedXY_;
  std::size_t cellCapacity_ = 0;
  TextureObject mask_;
  glm::ivec3 texels_{0};
};

}  // namespace spindrift
