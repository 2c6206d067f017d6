#pragma once

#include "framedata/PixelTiles.h"
#include "framedata/SmoothedDepth.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"

namespace spindrift {

/// Recomputes a depth layer's outward world normals from its smoothed depth (the liquid paper recomputes them
/// after plane fitting, whose fitted normals do not describe the smoothed surface).
class NormalsFromDepthPass {
 public:
  explicit NormalsFromDepthPass(const ShaderLibrary& shaders);
  /// `originalNormal` serves pixels whose depth has no neighbour along an axis. `backLayer` turns the normals
  /// away from the camera. With `tiles`, only the marked tiles are shaded and the rest cleared to no normal.
  RecomputedNormals run(const Texture2D& smoothedEyeDepth, const Texture2D& originalNormal, bool backLayer,
                        const PixelTiles* tiles, int width, int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D normal_;
};

}  // namespace spindrift
