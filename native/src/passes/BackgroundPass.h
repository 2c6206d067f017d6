#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "framedata/BackgroundData.h"
#include "framedata/BackgroundImages.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "io/ImageFiles.h"

namespace spindrift {

/// Resolves the background image over the environment or colour, and the solids' depth, per pixel.
class BackgroundPass {
 public:
  explicit BackgroundPass(const ShaderLibrary& shaders);
  BackgroundData run(const BackgroundImages& images, int width, int height);

 private:
  void upload(const BackgroundImages& images);

  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D imageTexture_;
  Texture2D depthTexture_;
  Texture2D environmentTexture_;
  Texture2D liquidDepthTexture_;
  Texture2D color_;
  Texture2D eyeDepth_;
  std::uint64_t uploadedGeneration_ = ~std::uint64_t(0);
};

}  // namespace spindrift
