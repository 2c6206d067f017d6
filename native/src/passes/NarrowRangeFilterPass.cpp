#include "passes/NarrowRangeFilterPass.h"

#include "passes/SeparableFilter.h"

namespace spindrift {

NarrowRangeFilterPass::NarrowRangeFilterPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "depth_narrow_range_filter.frag"})) {}

SmoothedDepth NarrowRangeFilterPass::run(const Texture2D& eyeDepth, float particleRadius,
                                         const LiquidParameters& parameters, DepthPingPong& targets) {
  const GLuint program = program_.id();
  glUseProgram(program);
  glUniform1f(uniformLocation(program, "filterRadius"), parameters.narrow_range_radius * particleRadius);
  glUniform1f(uniformLocation(program, "threshold"), parameters.narrow_range_threshold * particleRadius);
  glUniform1f(uniformLocation(program, "clampDistance"), parameters.narrow_range_clamp * particleRadius);
  glUniform1i(uniformLocation(program, "maximumRadiusInPixels"), kMaximumFilterRadiusInPixels);
  return {runSeparableFilter(program, eyeDepth, parameters.smoothing_iterations, targets)};
}

}  // namespace spindrift
