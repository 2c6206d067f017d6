#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/DensityMaskData.h"
#include "framedata/DepthLayers.h"
#include "framedata/RaymarchEntryData.h"
#include "framedata/RaymarchGridData.h"
#include "framedata/RaymarchSamples.h"
#include "framedata/RaymarchTileData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"
#include "spindrift/Scene.h"

namespace spindrift {

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
  const DomainBox* domain;  ///< A Mantaflow liquid's box, or null: the surface is clipped to it.
};

/// Adaptive ray marching of the density iso-surface (Wu et al., algorithm 1; shaders/raymarch_march.comp).
class RaymarchPass {
 public:
  explicit RaymarchPass(const ShaderLibrary& shaders);
  RaymarchSamples run(const RaymarchInputs& inputs, float particleRadius, const LiquidParameters& parameters,
                      int width, int height);
  RaymarchCounters counters() const;  ///< Of the last run (waits for the GPU).

 private:
  // liquid.raymarch_stepping's two marches, compiled apart (ADAPTIVE_STEPS): on llvmpipe a switch by uniform
  // made every adaptive sample pay for the uniform march's density too.
  ProgramObject adaptiveProgram_, uniformProgram_;
  BufferObject counters_;
  Texture2D depth_, normal_, steps_;
};

}  // namespace spindrift
