#include "passes/LiquidShadePass.h"

#include <glm/geometric.hpp>

#include "passes/FrameUniforms.h"

namespace spindrift {

LiquidShadePass::LiquidShadePass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "liquid_shade.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

LiquidData LiquidShadePass::run(const SurfaceData& surface, const BackgroundData& background,
                                const LiquidParameters& parameters, int width, int height) {
  ensureTexture(color_, GL_RGBA32F, width, height);
  glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, color_.id(), 0);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);

  const GLuint program = program_.id();
  glUseProgram(program);
  const float lightLength = glm::length(parameters.light_direction);
  const glm::vec3 light = lightLength > 0.0f ? parameters.light_direction / lightLength : glm::vec3(0, 0, 1);
  glUniform1i(uniformLocation(program, "hasEnvironment"), background.environment ? 1 : 0);
  glUniform3fv(uniformLocation(program, "backgroundColor"), 1, &background.fallbackColor.x);
  glUniform3fv(uniformLocation(program, "baseColor"), 1, &parameters.base_color.x);
  glUniform1f(uniformLocation(program, "ambient"), parameters.ambient);
  glUniform1f(uniformLocation(program, "specular"), parameters.specular);
  glUniform1f(uniformLocation(program, "shininess"), parameters.shininess);
  glUniform3fv(uniformLocation(program, "lightDirection"), 1, &light.x);
  glBindTextureUnit(0, surface.eyeDepth.id());
  glBindTextureUnit(1, surface.normal.id());
  glBindTextureUnit(2, background.environment ? background.environment->id() : 0);
  drawFullscreenTriangle(emptyVertexArray_.id());
  checkGlError("shading the liquid");
  return {color_};
}

}  // namespace spindrift
