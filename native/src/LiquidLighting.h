#pragma once

#include <optional>

#include "LightDepthLayers.h"
#include "gl/PassTimer.h"
#include "gl/ShaderLibrary.h"
#include "passes/CausticPass.h"
#include "passes/LiquidShadowPass.h"
#include "passes/LitBackgroundPass.h"
#include "prep/LightViews.h"

namespace spindrift {

/// Light through the liquid onto the background, for every light that sees the liquid: the liquid's depth
/// layers from the light, its shadow, its caustics (suns and spots, with light.caustics), the sky light
/// submerged points keep, and the background lit accordingly. Each step is timed as its own pass. Which of
/// them a frame runs is FramePlan's choice; this runs them when the plan has the lit background.
class LiquidLighting {
 public:
  explicit LiquidLighting(const ShaderLibrary& shaders);
  LitBackgroundData run(const LightingPreparation& lights, const Camera& camera,
                        const BackgroundData& background, float particleRadius, const Parameters& parameters,
                        PassTimer& timer);

 private:
  LightDepthLayers layers_;
  LiquidShadowPass shadow_;
  CausticPass caustics_;
  LitBackgroundPass litBackground_;
};

}  // namespace spindrift
