#pragma once

#include <array>
#include <cstdint>

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/RaymarchEntryPass.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// The spacing of the rays cast in each screen tile: R8UI, one texel per tile, level 0 (every pixel),
/// 1 (every second), 2 (every fourth) or 3 (no liquid, no rays).
struct RaymarchTileData {
  const Texture2D& levels;
  int tileSize;
};

/// Tiles at full, half and quarter resolution, and without liquid.
using TileHistogram = std::array<std::uint32_t, 4>;

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
