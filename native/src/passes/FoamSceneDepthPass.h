#pragma once

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/BackgroundPass.h"

namespace spindrift {

/// Foam passes 1 and 2: the eye depths of what can hide or cover foam.
struct FoamSceneDepth {
  const Texture2D& solidEyeDepth;  ///< R32F: the background's solids (BackgroundData::eyeDepth).
  const Texture2D& fluidEyeDepth;  ///< R32F: the liquid's first surface; 1e10 where there is none.
};

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
