#include "passes/PlaneFitPass.h"

#include "passes/FrameUniforms.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace spindrift {

int planeFitTapSpacing(int imageHeight, const LiquidParameters& parameters) {
  if (parameters.plane_fit_reference_height <= 0 || imageHeight <= 0) return 1;
  return std::max(1, int(std::lround(double(imageHeight) / double(parameters.plane_fit_reference_height))));
}

PlaneFitPass::PlaneFitPass(const ShaderLibrary& shaders)
    : shaders_(shaders), clearFramebuffer_(createFramebuffer()) {
  // The default window's programs with the others, beside the first preparation.
  const int halfWindow = LiquidParameters{}.plane_fit_window / 2;
  program(halfWindow, false, false);
  program(halfWindow, false, true);
  program(halfWindow, true, true);
  program(halfWindow, true, false);
}

GLuint PlaneFitPass::program(int halfWindow, bool packedInput, bool packedOutput) {
  ProgramObject& program = programs_[{halfWindow, packedInput, packedOutput}];
  if (!program)
    program = shaders_.program({"fullscreen.vert", "depth_plane_fit.frag"},
                               {"HALF_WINDOW " + std::to_string(halfWindow),
                                std::string("PACKED_INPUT ") + (packedInput ? "1" : "0"),
                                std::string("PACKED_OUTPUT ") + (packedOutput ? "1" : "0")});
  return program.id();
}

// The rounds read and write depth and normal packed except where they meet the layer (the first round reads
// its depth and normals) and the filters' common R32F result (the last round writes depth alone). Reading
// each tap once took the dam break's smoothing from 154-160 to 134-142 ms (close-up) and 37-40 to 33-36 ms
// (oblique), bit-identical (docs/frame-cost.md, session 47).
SmoothedDepth PlaneFitPass::run(const Texture2D& eyeDepth, const Texture2D& originalNormal,
                                float particleRadius, const LiquidParameters& parameters,
                                DepthPingPong& targets) {
  const int halfWindow = parameters.plane_fit_window / 2;
  const int iterations = parameters.smoothing_iterations;
  const int tapSpacing = planeFitTapSpacing(eyeDepth.height, parameters);
  const auto use = [&](bool packedInput, bool packedOutput) {
    const GLuint id = program(halfWindow, packedInput, packedOutput);
    glUseProgram(id);
    glUniform1i(uniformLocation(id, "tapSpacing"), tapSpacing);
    glUniform1f(uniformLocation(id, "sigma"), parameters.plane_fit_sigma * particleRadius);
  };
  glBindTextureUnit(1, originalNormal.id());
  if (iterations <= 1) {
    use(false, false);
    return {targets.drawRepeatedly(eyeDepth, iterations)};
  }
  for (Texture2D& texture : packed_)
    ensureTexture(texture, GL_RGBA32F, eyeDepth.width, eyeDepth.height);
  // Drawn over tiles, a round leaves the pixels outside them as they are: they must read as no surface.
  const float noSurface[4] = {0.0f, 0.0f, 0.0f, 1e10f};  // kNoSurfaceDepth in w
  if (targets.tiles())
    for (const Texture2D& texture : packed_)
      clearColorTargets(clearFramebuffer_.id(), {&texture}, noSurface);
  use(false, true);
  const Texture2D* current = &targets.drawInto(eyeDepth, packed_[0]);
  use(true, true);
  for (int round = 1; round < iterations - 1; ++round)
    current = &targets.drawInto(*current, current == &packed_[0] ? packed_[1] : packed_[0]);
  use(true, false);
  return {targets.draw(*current)};
}

}  // namespace spindrift
