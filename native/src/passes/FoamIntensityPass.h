#pragma once

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/FoamThicknessPass.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Foam pass 5: the foam's intensity, its opacity in the composite.
struct FoamIntensityData {
  const Texture2D& intensity;  ///< R32F: iota in [0, 1).
};

/// Turns thickness rho into intensity with the sigmoid iota(rho, rho_mod, rho_exp) (foam paper 2.3).
class FoamIntensityPass {
 public:
  explicit FoamIntensityPass(const ShaderLibrary& shaders);
  FoamIntensityData run(const FoamThicknessData& thickness, const FoamParameters& parameters, int width,
                        int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D intensity_;
};

}  // namespace spindrift
