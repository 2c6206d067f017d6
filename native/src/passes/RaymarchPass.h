#pragma once

#include <cstdint>
#include <optional>

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/BackgroundPass.h"
#include "passes/DensityMaskPass.h"
#include "passes/EllipsoidImpostorPass.h"
#include "passes/RaymarchEntryPass.h"
#include "passes/RaymarchGridPass.h"
#include "passes/RaymarchTilePass.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// The rays cast, at the pixels of each tile's lattice (other pixels hold no surface and zero steps).
struct RaymarchSamples {
  const Texture2D& depth;   ///< R32F eye depth of the iso-surface; 1e10 where the ray found none.
  const Texture2D& normal;  ///< RGBA16F blended world normal; w: 0 miss, 1 splash, 2 aggregate.
  const Texture2D& steps;   ///< R32F marching steps of the pixel's ray (0 where none was cast).
};

/// What the rays did, counted on the GPU.
struct RaymarchCounters {
  std::uint32_t rays = 0;
  std::uint32_t steps = 0;      ///< Loop iterations: skips through empty cells and density samples.
  std::uint32_t densities = 0;  ///< Density evaluations, bisection included.
  std::uint32_t hits = 0;
};

/// Everything a ray reads besides the particles.
struct RaymarchInputs {
  const RaymarchEntryData& entry;
  const RaymarchTileData& tiles;
  const RaymarchGridData& grid;
  const DensityMaskData& mask;
  const DepthLayer& aggregateFront;  ///< D_agg
  const DepthLayer& splashBack;
  const DepthLayer& aggregateBack;
  const BackgroundData& background;
  bool hasSplash;
  bool hasAggregate;
};

/// Adaptive ray marching of the density iso-surface (Wu et al., algorithm 1; shaders/raymarch_march.comp).
class RaymarchPass {
 public:
  explicit RaymarchPass(const ShaderLibrary& shaders);
  RaymarchSamples run(const RaymarchInputs& inputs, float particleRadius, const LiquidParameters& parameters,
                      int width, int height);
  RaymarchCounters counters() const;  ///< Of the last run (waits for the GPU).

 private:
  ProgramObject program_;
  BufferObject counters_;
  Texture2D depth_, normal_, steps_;
};

}  // namespace spindrift
