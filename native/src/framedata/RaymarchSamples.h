#pragma once

#include <cstdint>

#include "gl/GlObjects.h"

namespace spindrift {

/// The rays cast (RaymarchPass's output), at the pixels of each tile's lattice; other pixels hold no surface
/// and zero steps.
struct RaymarchSamples {
  const Texture2D& depth;   ///< R32F eye depth of the iso-surface; 1e10 where the ray found none.
  const Texture2D& normal;  ///< RGBA16F blended world normal; w: 0 miss, 1 splash, 2 aggregate.
  const Texture2D& steps;   ///< R32F marching steps of the pixel's ray (0 where none was cast).
};

/// What the rays did, counted on the GPU.
struct RaymarchCounters {
  std::uint32_t rays = 0;
  std::uint32_t steps = 0;  ///< Loop iterations: skips through empty cells, density samples, entry checks.
  std::uint32_t densities = 0;  ///< Density evaluations, bisection included.
  std::uint32_t hits = 0;
  std::uint32_t refinements = 0;  ///< Of the density evaluations, those of the bisection.
  /// Particles read by all density evaluations (the neighbour searches' work), low and high 32 bits.
  std::uint32_t particlesLow = 0, particlesHigh = 0;
};

}  // namespace spindrift
