#pragma once

#include <vector>

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/FoamSceneDepthPass.h"
#include "prep/FoamPreparation.h"

namespace spindrift {

/// Foam pass 3: the nearest foam sphere per pixel, and the uploaded particles the thickness pass draws again.
struct FoamSurfaceData {
  const Texture2D& depthAndSearchRadius;  ///< RG32F: planar eye depth (1e10 where none), search radius h.
  const Texture2D& normal;                ///< RGBA16F: world normal, coverage.
  const BufferObject& particles;          ///< FoamInstance[count], shader storage.
  GLsizei count;
};

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
