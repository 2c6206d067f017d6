#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/DepthLayers.h"
#include "framedata/LightData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// Applies the shadow and caustic sums and the sky light each point keeps (below the liquid's surface, and
/// past other liquid) to the background (shaders/lit_background.frag): exactly through Cycles' light passes
/// when the background has them, else with light.direct_fraction. The sky light is upsampled from the sky
/// occlusion's samples where that pass ran, else found below the surface at every pixel from the sky's view,
/// which must then be bound at binding 2 (LightDepthLayers) when `run` runs (no LampLight::light then).
class LitBackgroundPass {
 public:
  explicit LitBackgroundPass(const ShaderLibrary& shaders);
  /// With `tiles` (LitTilePass), the lit tiles are shaded and the others get the background as it is.
  LitBackgroundData run(const BackgroundData& background, const LampLight& lamps, const CausticData& caustics,
                        const SkyView& sky, const Parameters& parameters, const LitTiles* tiles, int width,
                        int height);

 private:
  ProgramObject program_;            // finds what points below the surface keep (no sky occlusion)
  ProgramObject upsamplingProgram_;  // upsamples the sky occlusion's samples, which hold it
  ProgramObject shadowingProgram_;   // upsamples them and finds the one light's shadow itself
  ProgramObject plainProgram_;       // the tiles where no light changes the background (PLAIN)
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D color_;
  Texture2D liquidShadow_;
  Texture2D caustics_;
  Texture2D skyKept_;
};

}  // namespace spindrift
