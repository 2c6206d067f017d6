#pragma once

#include <array>

#include "framedata/PixelTiles.h"
#include "gl/GlObjects.h"

namespace spindrift {

/// Two R32F eye-depth render targets that the iterative smoothing filters alternate between, and the
/// fullscreen draw into one of them. One instance serves every filter of a DepthSmoothingPass, since only one
/// filter runs per layer.
class DepthPingPong {
 public:
  DepthPingPong();

  /// Makes both targets width × height (reallocated only when the size changes). With `tiles`, later draws
  /// shade only the marked tiles and both targets are cleared to kNoSurfaceDepth, which every filter writes
  /// where the layer is empty ("smoothing never creates a surface").
  void prepare(int width, int height, const PixelTiles* tiles);
  /// Draws the current program's fullscreen triangle (shaders/fullscreen.vert), or the marked tiles, with
  /// `source` at texture unit 0 into the target that is not `source`, and returns that target.
  const Texture2D& draw(const Texture2D& source);
  /// Draws `count` times, each reading the previous result, starting from `source`; returns the last result
  /// (`source` itself when `count` is 0).
  const Texture2D& drawRepeatedly(const Texture2D& source, int count);
  /// Draws as draw() does into `target`, a texture of the targets' size that is not `source` (a filter's
  /// own intermediate format); returns it.
  const Texture2D& drawInto(const Texture2D& source, const Texture2D& target);
  /// The tiles later draws shade (null: every pixel), as prepare() was given them.
  const PixelTiles* tiles() const { return tiles_; }
  /// Copies `source` into a target and returns it.
  const Texture2D& copy(const Texture2D& source);

 private:
  Texture2D& targetOtherThan(const Texture2D& source);

  std::array<Texture2D, 2> targets_;
  const PixelTiles* tiles_ = nullptr;
  FramebufferObject framebuffer_;
  VertexArrayObject emptyVertexArray_;
};

}  // namespace spindrift
