#pragma once

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/FoamDepthPass.h"
#include "passes/FoamIntensityPass.h"
#include "passes/FoamOcclusionPass.h"
#include "passes/FoamThicknessPass.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Foam pass 7: the foam layer the composite puts over the liquid and background, and its parts.
struct FoamLayerData {
  const Texture2D& foam;        ///< RGBA32F premultiplied: iota (I_final - zeta_final), alpha iota.
  const Texture2D& spray;       ///< RGBA32F: the part of `foam` from spray (by share of thickness).
  const Texture2D& surface;     ///< RGBA32F: from surface foam.
  const Texture2D& bubble;      ///< RGBA32F: from bubbles.
  const Texture2D& shadow;      ///< RGBA16F: zeta_final in rgb.
  const Texture2D& irradiance;  ///< RGBA16F: I_final in rgb.
  const Texture2D& thickness;   ///< The thickness pass's per-type thickness, for the output's foam_thickness.
};

/// Blurs the shadow and irradiance (Gaussian, radius 3/2 h_screen), colours the shadow, scales the irradiance
/// and makes the foam layer (foam paper 2.5).
class FoamBlurPass {
 public:
  explicit FoamBlurPass(const ShaderLibrary& shaders);
  FoamLayerData run(const FoamSurfaceData& surface, const FoamThicknessData& thickness,
                    const FoamIntensityData& intensity, const FoamOcclusionData& occlusion,
                    const FoamParameters& parameters, int width, int height);

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
