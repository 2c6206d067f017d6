#pragma once

#include <glm/vec3.hpp>

#include "gl/GlObjects.h"

namespace spindrift {

/// The compact 3D density mask (DensityMaskPass's output): an R8UI 3D texture of gridSize / 2 texels, bit
/// (x & 1) | (y & 1) << 1 | (z & 1) << 2 of texel cell / 2 set where the cell may hold the iso-surface.
struct DensityMaskData {
  const TextureObject& mask;
  glm::ivec3 texels;
};

}  // namespace spindrift
