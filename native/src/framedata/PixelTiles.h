#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// The side of a pixel tile, in pixels: a quarter of llvmpipe's 64-pixel bin, so a tile's point covers one
/// whole 16 × 16 rasterizer block and the tile list follows a silhouette within 16 pixels (tiles of 8 took
/// the dam break's smoothing and refraction from 41 and 45 to 50 and 53 ms, drawn as two triangles each).
constexpr int kPixelTileSize = 16;

/// Tiles across and down a width × height frame.
inline int pixelTilesAcross(int width) {
  return (width + kPixelTileSize - 1) / kPixelTileSize;
}
inline int pixelTilesDown(int height) {
  return (height + kPixelTileSize - 1) / kPixelTileSize;
}

/// The texture unit of fullscreen.vert's drawnTiles, which no fragment shader uses.
constexpr unsigned kPixelTilesTextureUnit = 15;

/// The screen's 16 × 16 pixel tiles that hold any pixel of the liquid's depth layers (PixelTilePass's
/// output): R8UI, one texel per tile, 1 where a pass that only changes liquid pixels must run, 0 where it
/// would write only its "no liquid" values. drawFullscreen (FrameUniforms.h) draws a quad for each marked
/// tile.
struct PixelTiles {
  const Texture2D& marked;
};

}  // namespace spindrift
