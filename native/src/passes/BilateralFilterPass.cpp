#include "passes/BilateralFilterPass.h"

#include "passes/SeparableFilter.h"

namespace spindrift {

BilateralFilterPass::BilateralFilterPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "depth_bilateral_filter.frag"})) {}

SmoothedDepth BilateralFilterPass::run(const Texture2D& eyeDepth, float particleRadius,
                                       const LiquidParameters& parameters, DepthPingPong& targets) {
  const GLuint program = program_.id();
  glUseProgram(program);
  glUniform1f(uniformLocation(program, "spatialSigma"), parameters.bilateral_spatial_sigma * particleRadius);
  glUniform1f(uniformLocation(program, "depthSigma"), parameters.bilateral_depth_sigma * particleRadius);
  glUniform1i(uniformLocation(program, "maximumRadiusInPixels"), kMaximumFilterRadiusInPixels);
  return {runSeparableFilter(program, eyeDepth, parameters.smoothing_iterations, targets)};
}

}  // namespace spindrift
