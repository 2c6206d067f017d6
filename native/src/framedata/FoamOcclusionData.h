#pragma once

#include <cstdint>

#include "gl/GlObjects.h"

namespace spindrift {

/// Foam pass 6: how much light each foam pixel receives.
struct FoamOcclusionData {
  const Texture2D& shadow;      ///< RG32F: zeta in [0, 1], and the eye depth it was estimated at.
  const Texture2D& irradiance;  ///< RGBA16F: I in rgb.
};

/// What the occlusion pass did, counted on the GPU.
struct FoamOcclusionStatistics {
  std::uint32_t foamPixels = 0;
  std::uint32_t estimates = 0;  ///< Pixels, or blocks (foam.occlusion_block > 1), whose SSAO was estimated.
  std::uint64_t samples = 0;    ///< SSAO samples generated (nu summed over passes and pixels).
};

}  // namespace spindrift
