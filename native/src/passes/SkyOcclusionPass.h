#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/DepthLayers.h"
#include "framedata/LightData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "prep/LightViews.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// The sky and bounced light a background point keeps past liquid that is not above it: the floor beside a
/// block of water, under a floating ball (shaders/sky_occlusion.frag), one sample per scale² pixels
/// (skyOcclusionScale). The sky's view must be bound at binding 2 (LightDepthLayers) when `run` runs.
class SkyOcclusionPass {
 public:
  explicit SkyOcclusionPass(const ShaderLibrary& shaders);
  /// `skyLayers`: the liquid seen from straight above (LightingPreparation::sky), whose view is `sky`.
  SkyOcclusionData run(const SurfaceLayers& skyLayers, const LightView& sky, const LiquidBounds& bounds,
                       const BackgroundData& background, const Parameters& parameters, int scale, int width,
                       int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D kept_;
};

}  // namespace spindrift
