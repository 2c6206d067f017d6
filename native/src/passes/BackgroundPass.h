#pragma once

#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "io/ImageFiles.h"

namespace spindrift {

/// The background of one frame on the CPU, already at the camera's size. Null images are absent.
struct BackgroundImages {
  const FloatImage* color = nullptr;        ///< RGBA, premultiplied.
  const FloatImage* eyeDepth = nullptr;     ///< Planar eye depth, one channel.
  const FloatImage* environment = nullptr;  ///< Equirectangular RGBA, any size.
  const FloatImage* liquidEyeDepth = nullptr;  ///< Planar eye depth of a render that includes the liquid.
  /// From Cycles' light passes: direct diffuse, direct glossy and indirect light (RGBA each), or null.
  const std::array<FloatImage, 3>* lightPasses = nullptr;
  glm::vec3 fallbackColor{0.0f};
  std::uint64_t generation = 0;  ///< Changes whenever any image changes, so unchanged ones stay uploaded.
};

/// What lies behind the liquid, on the GPU, at the camera's size.
struct BackgroundData {
  const Texture2D& color;     ///< RGBA32F, opaque.
  const Texture2D& eyeDepth;  ///< R32F planar eye depth; 1e10 where nothing is.
  const Texture2D* environment;  ///< Null when the scene has none.
  glm::vec3 fallbackColor;
  /// R32F planar eye depth of a render that includes the liquid, as the file has it; null when none.
  const Texture2D* liquidEyeDepth;
  /// Direct diffuse (DiffCol x DiffDir), direct glossy (GlossCol x GlossDir) and indirect light (DiffCol x
  /// DiffInd + GlossCol x GlossInd), RGBA32F each, from Cycles' light passes; null when the image has none.
  const Texture2D* lightPasses = nullptr;
};

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
  Texture2D lightPassTextures_[3];
  Texture2D color_;
  Texture2D eyeDepth_;
  std::uint64_t uploadedGeneration_ = ~std::uint64_t(0);
};

}  // namespace spindrift
