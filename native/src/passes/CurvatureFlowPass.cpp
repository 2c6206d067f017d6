#include "passes/CurvatureFlowPass.h"

namespace spindrift {

CurvatureFlowPass::CurvatureFlowPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "depth_curvature_flow.frag"})) {}

SmoothedDepth CurvatureFlowPass::run(const Texture2D& eyeDepth, const LiquidParameters& parameters,
                                     DepthPingPong& targets) {
  const GLuint program = program_.id();
  glUseProgram(program);
  glUniform1f(uniformLocation(program, "timeStep"), parameters.curvature_flow_time_step);
  return {targets.drawRepeatedly(eyeDepth, parameters.curvature_flow_steps)};
}

}  // namespace spindrift
