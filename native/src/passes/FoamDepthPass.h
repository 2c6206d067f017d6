#pragma once

#include <vector>

#include "framedata/FoamSceneDepth.h"
#include "framedata/FoamSurfaceData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "prep/FoamPreparation.h"

namespace spindrift {

/// Draws foam particles as sprites with spherical depth (foam paper 2.1), keeping the nearest per pixel.
class FoamDepthPass {
 public:
  explicit FoamDepthPass(const ShaderLibrary& shaders);
  FoamSurfaceData run(const std::vector<FoamInstance>& particles, const FoamSceneDepth& scene, int width,
                      int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  BufferObject particleBuffer_;
  std::size_t particleBufferBytes_ = 0;
  Texture2D depthAndSearchRadius_;
  Texture2D normal_;
  Texture2D depthBuffer_;
};

}  // namespace spindrift
