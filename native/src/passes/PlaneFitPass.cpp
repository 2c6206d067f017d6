#include "passes/PlaneFitPass.h"

#include <algorithm>
#include <cmath>

#include "passes/FrameUniforms.h"

namespace spindrift {

int planeFitTapSpacing(int imageHeight, const LiquidParameters& parameters) {
  if (parameters.plane_fit_reference_height <= 0 || imageHeight <= 0) return 1;
  return std::max(1, int(std::lround(double(imageHeight) / double(parameters.plane_fit_reference_height))));
}

PlaneFitPass::PlaneFitPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "depth_plane_fit.frag"})),
      packProgram_(shaders.program({"fullscreen.vert", "plane_fit_pack.frag"})),
      framebuffer_(createFramebuffer()),
      emptyVertexArray_(createVertexArray()) {}

void PlaneFitPass::drawInto(const Texture2D& target) {
  bindColorTargets(framebuffer_.id(), {&target});
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  drawFullscreenTriangle(emptyVertexArray_.id());
}

SmoothedDepth PlaneFitPass::run(const Texture2D& eyeDepth, const Texture2D& originalNormal,
                                float particleRadius, const LiquidParameters& parameters,
                                DepthPingPong& targets) {
  const int iterations = parameters.smoothing_iterations;
  if (iterations <= 0) return {eyeDepth};
  // Each tap reads the neighbour's depth and original normal: packed into one texel first, and carried from
  // iteration to iteration in RGBA32F targets; the last iteration writes the depth alone into `targets`.
  for (Texture2D& texture : packed_)
    ensureTexture(texture, GL_RGBA32F, eyeDepth.width, eyeDepth.height);
  glUseProgram(packProgram_.id());
  glBindTextureUnit(0, eyeDepth.id());
  glBindTextureUnit(1, originalNormal.id());
  drawInto(packed_[0]);
  checkGlError("packing the plane fit's input");

  const GLuint program = program_.id();
  glUseProgram(program);
  glUniform1i(uniformLocation(program, "halfWindow"), parameters.plane_fit_window / 2);
  glUniform1i(uniformLocation(program, "tapSpacing"), planeFitTapSpacing(eyeDepth.height, parameters));
  glUniform1f(uniformLocation(program, "sigma"), parameters.plane_fit_sigma * particleRadius);
  const Texture2D* current = &packed_[0];
  for (int iteration = 1; iteration < iterations; ++iteration) {
    const Texture2D& next = current == &packed_[0] ? packed_[1] : packed_[0];
    glBindTextureUnit(0, current->id());
    drawInto(next);
    checkGlError("fitting planes to a depth layer");
    current = &next;
  }
  return {targets.draw(*current)};
}

}  // namespace spindrift
