#pragma once

#include "framedata/RaymarchEntryData.h"
#include "framedata/RaymarchTileData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Adaptive ray casting resolution (adaptive ray marching paper, 4.3; shaders/raymarch_tiles.comp).
class RaymarchTilePass {
 public:
  explicit RaymarchTilePass(const ShaderLibrary& shaders);
  RaymarchTileData run(const RaymarchEntryData& entry, float particleRadius,
                       const LiquidParameters& parameters, int width, int height);
  /// How many tiles of the last run got each level (waits for the GPU).
  TileHistogram histogram() const;

 private:
  ProgramObject program_;
  BufferObject histogram_;
  Texture2D levels_;
};

/// liquid.raymarch_tile_size rounded up to a multiple of 4, so every ray lattice is aligned with the tiles.
int raymarchTileSize(const LiquidParameters& parameters);

}  // namespace spindrift
