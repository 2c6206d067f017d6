#pragma once

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
  /// away from the camera.
  RecomputedNormals run(const Texture2D& smoothedEyeDepth, const Texture2D& originalNormal, bool backLayer,
                        int width, int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D normal_;
};

}  // namespace spindrift
