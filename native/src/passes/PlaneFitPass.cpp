#include "passes/PlaneFitPass.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace spindrift {

int planeFitTapSpacing(int imageHeight, const LiquidParameters& parameters) {
  if (parameters.plane_fit_reference_height <= 0 || imageHeight <= 0) return 1;
  return std::max(1, int(std::lround(double(imageHeight) / double(parameters.plane_fit_reference_height))));
}

PlaneFitPass::PlaneFitPass(const ShaderLibrary& shaders) : shaders_(shaders) {
  program(LiquidParameters{}.plane_fit_window / 2);  // with the other programs, beside the first preparation
}

GLuint PlaneFitPass::program(int halfWindow) {
  ProgramObject& program = programs_[halfWindow];
  if (!program)
    program = shaders_.program({"fullscreen.vert", "depth_plane_fit.frag"},
                               {"HALF_WINDOW " + std::to_string(halfWindow)});
  return program.id();
}

SmoothedDepth PlaneFitPass::run(const Texture2D& eyeDepth, const Texture2D& originalNormal,
                                float particleRadius, const LiquidParameters& parameters,
                                DepthPingPong& targets) {
  const GLuint program = this->program(parameters.plane_fit_window / 2);
  glUseProgram(program);
  glUniform1i(uniformLocation(program, "tapSpacing"), planeFitTapSpacing(eyeDepth.height, parameters));
  glUniform1f(uniformLocation(program, "sigma"), parameters.plane_fit_sigma * particleRadius);
  glBindTextureUnit(1, originalNormal.id());
  return {targets.drawRepeatedly(eyeDepth, parameters.smoothing_iterations)};
}

}  // namespace spindrift
