#include "passes/PlaneFitPass.h"

namespace spindrift {

PlaneFitPass::PlaneFitPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "depth_plane_fit.frag"})) {}

SmoothedDepth PlaneFitPass::run(const Texture2D& eyeDepth, const Texture2D& originalNormal,
                                float particleRadius, const LiquidParameters& parameters,
                                DepthPingPong& targets) {
  const GLuint program = program_.id();
  glUseProgram(program);
  glUniform1i(uniformLocation(program, "halfWindow"), parameters.plane_fit_window / 2);
  glUniform1f(uniformLocation(program, "sigma"), parameters.plane_fit_sigma * particleRadius);
  glBindTextureUnit(1, originalNormal.id());
  return {targets.drawRepeatedly(eyeDepth, parameters.smoothing_iterations)};
}

}  // namespace spindrift
