#pragma once

#include <cstdint>

#include "framedata/BackgroundData.h"
#include "framedata/LightData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"

namespace spindrift {

/// Marks the pixel tiles where the lights change the background, from the sky occlusion's samples, the
/// caustics and the one light's columns or the shadow pass's sums (shaders/lit_tiles.comp), so that the lit
/// background shades only those (light.skip_unlit_tiles; docs/frame-cost.md). With `lamps.light`, that
/// light's view must be bound at binding 2 (LightDepthLayers) when `run` runs, as for LitBackgroundPass.
class LitTilePass {
 public:
  explicit LitTilePass(const ShaderLibrary& shaders);
  LitTiles run(const BackgroundData& background, const LampLight& lamps, const CausticData& caustics,
               const SkyOcclusionData& sky, int width, int height);
  /// How many tiles the last run marked lit (waits for the GPU).
  std::uint32_t litTiles() const;

 private:
  ProgramObject program_;           // the shadow pass's sums
  ProgramObject shadowingProgram_;  // the one light's columns (SHADOW_IN_PLACE)
  BufferObject counter_;
  Texture2D lit_;
  Texture2D plain_;
};

}  // namespace spindrift
