#pragma once

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/BackgroundPass.h"
#include "passes/CausticPass.h"
#include "passes/LiquidShadowPass.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// The background as the liquid lights it, and the passes that say how.
struct LitBackgroundData {
  BackgroundData background;      ///< The original with `color` replaced by the lit colour.
  const Texture2D& liquidShadow;  ///< RGBA32F: what each point keeps of the lights' direct light (rgb).
  const Texture2D& caustics;      ///< RGBA32F: the direct light the liquid refracts onto each point (rgb).
  const Texture2D& skyKept;       ///< RGBA32F: what a submerged point keeps of the sky and bounced light.
};

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
