#pragma once

#include <array>
#include <cstdint>

#include "gl/GlObjects.h"

namespace spindrift {

/// The spacing of the rays cast in each screen tile (RaymarchTilePass's output): R8UI, one texel per tile,
/// level 0 (every pixel), 1 (every second), 2 (every fourth) or 3 (no liquid, no rays).
struct RaymarchTileData {
  const Texture2D& levels;
  int tileSize;
};

/// Tiles at full, half and quarter resolution, and without liquid.
using TileHistogram = std::array<std::uint32_t, 4>;

}  // namespace spindrift
