#pragma once

#include "framedata/FoamIntensityData.h"
#include "framedata/FoamLayerData.h"
#include "framedata/FoamOcclusionData.h"
#include "framedata/FoamSurfaceData.h"
#include "framedata/FoamThicknessData.h"
#include "framedata/PixelTiles.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Blurs the shadow and irradiance (Gaussian, radius 3/2 h_screen), colours the shadow, scales the irradiance
/// and makes the foam layer (foam paper 2.5).
class FoamBlurPass {
 public:
  explicit FoamBlurPass(const ShaderLibrary& shaders);
  /// With `tiles` (marking every tile with a foam pixel: the blur averages foam pixels only, so nothing
  /// spreads beyond them) only those tiles are shaded, the rest cleared to the no-foam values.
  FoamLayerData run(const FoamSurfaceData& surface, const FoamThicknessData& thickness,
                    const FoamIntensityData& intensity, const FoamOcclusionData& occlusion,
                    const FoamParameters& parameters, const PixelTiles* tiles, int width, int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D horizontalShadow_;
  Texture2D horizontalIrradiance_;
  Texture2D foam_;
  Texture2D spray_;
  Texture2D surface_;
  Texture2D bubble_;
  Texture2D shadow_;
  Texture2D irradiance_;
};

}  // namespace spindrift
