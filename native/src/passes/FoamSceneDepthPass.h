#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/FoamSceneDepth.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"

namespace spindrift {

/// Resolves the liquid's depth from the liquid pipeline's first surface (use a: liquid drawn by Spindrift),
/// the depth pass of a render that includes the liquid (use b: background.liquid_depth), or the nearer of
/// both.
class FoamSceneDepthPass {
 public:
  explicit FoamSceneDepthPass(const ShaderLibrary& shaders);
  /// `liquidFrontDepth` is null when the frame drew no liquid.
  FoamSceneDepth run(const BackgroundData& background, const Texture2D* liquidFrontDepth, int width,
                     int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D fluidEyeDepth_;
};

}  // namespace spindrift
