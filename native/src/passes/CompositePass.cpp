#include "passes/CompositePass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {

CompositePass::CompositePass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "composite.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

CompositeData CompositePass::run(const BackgroundData& background, const LiquidData* liquid,
                                 const FoamLayerData* foam, int width, int height) {
  ensureTexture(color_, GL_RGBA32F, width, height);
  glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, color_.id(), 0);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(program_.id());
  glBindTextureUnit(0, background.color.id());
  glUniform1i(uniformLocation(program_.id(), "hasLiquid"), liquid ? 1 : 0);
  glBindTextureUnit(1, liquid ? liquid->color.id() : 0);
  glUniform1i(uniformLocation(program_.id(), "hasFoam"), foam ? 1 : 0);
  glBindTextureUnit(2, foam ? foam->foam.id() : 0);
  drawFullscreenTriangle(emptyVertexArray_.id());
  checkGlError("compositing");
  return {color_};
}

}  // namespace spindrift
