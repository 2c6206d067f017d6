#pragma once

#include "framedata/FoamIntensityData.h"
#include "framedata/FoamThicknessData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"

namespace spindrift {

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
