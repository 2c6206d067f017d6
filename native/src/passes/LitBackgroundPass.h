#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/LightData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Applies the shadow, caustic and sky sums to the background (shaders/lit_background.frag): exactly through
/// Cycles' light passes when the background has them, else with light.direct_fraction.
class LitBackgroundPass {
 public:
  explicit LitBackgroundPass(const ShaderLibrary& shaders);
  LitBackgroundData run(const BackgroundData& background, const LiquidShadowData& shadows,
                        const CausticData& caustics, const LightParameters& parameters, int width,
                        int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D color_;
  Texture2D liquidShadow_;
  Texture2D caustics_;
  Texture2D skyKept_;
};

}  // namespace spindrift
