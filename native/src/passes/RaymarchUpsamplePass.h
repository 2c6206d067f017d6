#pragma once

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/EllipsoidImpostorPass.h"
#include "passes/RaymarchPass.h"
#include "passes/RaymarchTilePass.h"

namespace spindrift {

/// The marched first surface at full resolution, written into the front layers the refraction pass reads.
struct MarchedFronts {
  DepthLayer splashFront;
  DepthLayer aggregateFront;
};

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
