#include "passes/PlaneFitPass.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "passes/FrameUniforms.h"

namespace spindrift {

int planeFitTapSpacing(int imageHeight, const LiquidParameters& parameters) {
  if (parameters.plane_fit_reference_height <= 0 || imageHeight <= 0) return 1;
  return std::max(1, int(std::lround(double(imageHeight) / double(parameters.plane_fit_reference_height))));
}

PlaneFitPass::PlaneFitPass(const ShaderLibrary& shaders)
    : shaders_(shaders),
      packProgram_(shaders.program({"fullscreen.vert", "depth_plane_fit_pack.frag"})),
      clearFramebuffer_(createFramebuffer()) {
  // The default window's programs with the others, beside the first preparation.
  const int halfWindow = LiquidParameters{}.plane_fit_window / 2;
  program(halfWindow, true);
  program(halfWindow, false);
}

GLuint PlaneFitPass::program(int halfWindow, bool packedOutput) {
  ProgramObject& program = programs_[{halfWindow, packedOutput}];
  if (!program)
    program = shaders_.program({"fullscreen.vert", "depth_plane_fit.frag"},
                               {"HALF_WINDOW " + std::to_string(halfWindow),
                                std::string("PACKED_OUTPUT ") + (packedOutput ? "1" : "0")});
  return program.id();
}

// The rounds read and write depth and normal packed: depth_plane_fit_pack.frag packs the layer's depth and
// normals first, and the last round writes the filters' common R32F depth alone. Reading each tap once took
// the dam break's smoothing from 154-160 to 134-142 ms (close-up) and 37-40 to 33-36 ms (oblique) with the
// first round still reading the layer, and packing first took 7-12 % more, bit-identical (docs/frame-cost.md,
// session 47).
SmoothedDepth PlaneFitPass::run(const Texture2D& eyeDepth, const Texture2D& originalNormal,
                                float particleRadius, const LiquidParameters& parameters,
                                DepthPingPong& targets) {
  const int halfWindow = parameters.plane_fit_window / 2;
  const int iterations = parameters.smoothing_iterations;
  const int tapSpacing = planeFitTapSpacing(eyeDepth.height, parameters);
  const auto use = [&](bool packedOutput) {
    const GLuint id = program(halfWindow, packedOutput);
    glUseProgram(id);
    glUniform1i(uniformLocation(id, "tapSpacing"), tapSpacing);
    glUniform1f(uniformLocation(id, "sigma"), parameters.plane_fit_sigma * particleRadius);
  };
  if (iterations <= 0) return {eyeDepth};
  // The taps beyond the image read the border, no surface, as a test of each tap's position did.
  const float noSurface[4] = {0.0f, 0.0f, 0.0f, 1e10f};  // kNoSurfaceDepth in w
  for (Texture2D& texture : packed_) {
    ensureTexture(texture, GL_RGBA32F, eyeDepth.width, eyeDepth.height);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    glTextureParameterfv(texture.id(), GL_TEXTURE_BORDER_COLOR, noSurface);
  }
  // Drawn over tiles, a round leaves the pixels outside them as they are: they must read as no surface.
  if (targets.tiles())
    for (const Texture2D& texture : packed_)
      clearColorTargets(clearFramebuffer_.id(), {&texture}, noSurface);
  glUseProgram(packProgram_.id());
  glBindTextureUnit(1, originalNormal.id());
  const Texture2D* current = &targets.drawInto(eyeDepth, packed_[0]);
  use(true);
  for (int round = 0; round < iterations - 1; ++round)
    current = &targets.drawInto(*current, current == &packed_[0] ? packed_[1] : packed_[0]);
  use(false);
  return {targets.draw(*current)};
}

}  // namespace spindrift
