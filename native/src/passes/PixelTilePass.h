#pragma once

#include <cstdint>
#include <vector>

#include "framedata/PixelTiles.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"

namespace spindrift {

/// Marks the pixel tiles that hold any surface of the given depth layers (shaders/pixel_tiles.comp), so the
/// liquid passes after it shade those tiles only (liquid.skip_empty_tiles; docs/frame-cost.md).
class PixelTilePass {
 public:
  explicit PixelTilePass(const ShaderLibrary& shaders);
  /// `eyeDepths`: one to four R32F layers, kNoSurfaceDepth where empty (or the foam intensity, 0 there).
  PixelTiles run(const std::vector<const Texture2D*>& eyeDepths, int width, int height);
  /// How many tiles the last run marked (waits for the GPU).
  std::uint32_t markedTiles() const;

 private:
  ProgramObject program_;
  BufferObject counter_;
  Texture2D marked_;
};

}  // namespace spindrift
