#pragma once

#include <optional>

#include "LightDepthLayers.h"
#include "gl/PassTimer.h"
#include "gl/ShaderLibrary.h"
#include "passes/CausticPass.h"
#include "passes/LiquidShadowPass.h"
#include "passes/LitBackgroundPass.h"
#include "passes/LitTilePass.h"
#include "passes/SkyOcclusionPass.h"
#include "prep/LightViews.h"

namespace spindrift {

/// Light through the liquid onto the background, for every light that sees the liquid: the liquid's depth
/// layers from the light, its shadow, its caustics (suns and spots, with light.caustics), the sky light
/// points keep below the liquid and past it, and the background lit accordingly. Each step is timed as its
/// own pass. Which of them a frame runs is FramePlan's choice; this runs them when the plan has the lit
/// background.
class LiquidLighting {
 public:
  explicit LiquidLighting(const ShaderLibrary& shaders);
  /// `occludeSky`: the plan runs the sky occlusion (points outside the liquid lose the sky light it takes);
  /// `shadowPass`: the plan runs the shadow pass, else the lit background finds the one light's shadow;
  /// `litTiles`: the plan marks the tiles the lights change (which needs `occludeSky`), and the lit
  /// background shades only those.
  LitBackgroundData run(const LightingPreparation& lights, const Camera& camera,
                        const BackgroundData& background, float particleRadius, const Parameters& parameters,
                        bool occludeSky, bool shadowPass, bool litTiles, PassTimer& timer);
  /// How many tiles the last frame's lit background shaded (waits for the GPU).
  std::uint32_t litTilesShaded() const { return litTiles_.litTiles(); }
  /// Pixels per sample along each axis of the last frame's sky occlusion (skyOcclusionScale); 0 when it did
  /// not run.
  int skyOcclusionScale() const { return skyOcclusionScale_; }

 private:
  /// One light's depth layers, its shadow (`withShadowPass`) and its caustics (suns and spots, with
  /// light.caustics); returns the layers, whose view it leaves bound at binding 2.
  SurfaceLayers drawLight(const LightPreparation& light, const Camera& camera,
                          const BackgroundData& background, float particleRadius,
                          const Parameters& parameters, bool withShadowPass, PassTimer& timer);

  LightDepthLayers layers_;
  LiquidShadowPass shadow_;
  SkyOcclusionPass skyOcclusion_;
  CausticPass caustics_;
  LitTilePass litTiles_;
  int skyOcclusionScale_ = 0;
  LitBackgroundPass litBackground_;
};

}  // namespace spindrift
