#pragma once

#include "framedata/DepthLayers.h"
#include "framedata/MarchedFronts.h"
#include "framedata/RaymarchSamples.h"
#include "framedata/RaymarchTileData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"

namespace spindrift {

/// Interpolates the rays of half- and quarter-resolution tiles back to every pixel and splits the surface by
/// class into the splash and aggregate fronts (shaders/raymarch_upsample.comp).
class RaymarchUpsamplePass {
 public:
  explicit RaymarchUpsamplePass(const ShaderLibrary& shaders);
  /// `splashFront` and `aggregateFront` are the impostor layers: kept where they lie behind the marched
  /// surface.
  MarchedFronts run(const RaymarchSamples& samples, const RaymarchTileData& tiles,
                    const DepthLayer& splashFront, const DepthLayer& aggregateFront, int width, int height);

 private:
  ProgramObject program_;
  Texture2D splashDepth_, splashNormal_, aggregateDepth_, aggregateNormal_;
};

}  // namespace spindrift
