#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/DepthLayers.h"
#include "framedata/LightData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// The sky's view of the liquid, which the lit background finds the sky light each point keeps from.
struct SkyView {
  const SurfaceLayers& layers;        ///< The liquid seen from straight above (LightDepthLayers).
  const SkyOcclusionData* occlusion;  ///< The sky occlusion's samples, or null when it did not run.
  float particleRadius;               ///< Points two radii below the drawn bottom still lie in it.
};

/// Where the lit background gets the lamps' direct light from: the shadow pass's sums over the lights, or the
/// one light whose shadow it finds itself (its caustics on, and the sky occlusion's samples there), whose
/// view must then be bound at binding 2 (LightDepthLayers) when `run` runs.
struct LampLight {
  const LiquidShadowData* sums = nullptr;
  const Light* light = nullptr;
  const SurfaceLayers* layers = nullptr;  ///< The one light's.
};

/// Applies the shadow and caustic sums and the sky light each point keeps (below the liquid's surface, and
/// past other liquid) to the background (shaders/lit_background.frag): exactly through Cycles' light passes
/// when the background has them, else with light.direct_fraction. The sky light is upsampled from the sky
/// occlusion's samples where that pass ran, else found below the surface at every pixel from the sky's view,
/// which must then be bound at binding 2 (LightDepthLayers) when `run` runs (no LampLight::light then).
class LitBackgroundPass {
 public:
  explicit LitBackgroundPass(const ShaderLibrary& shaders);
  LitBackgroundData run(const BackgroundData& background, const LampLight& lamps, const CausticData& caustics,
                        const SkyView& sky, const Parameters& parameters, int width, int height);

 private:
  ProgramObject program_;            // finds what points below the surface keep (no sky occlusion)
  ProgramObject upsamplingProgram_;  // upsamples the sky occlusion's samples, which hold it
  ProgramObject shadowingProgram_;   // upsamples them and finds the one light's shadow itself
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D color_;
  Texture2D liquidShadow_;
  Texture2D caustics_;
  Texture2D skyKept_;
};

}  // namespace spindrift
