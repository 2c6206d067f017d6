#include "passes/LiquidShadowPass.h"

#include "passes/FrameUniforms.h"
#include "passes/LightUniforms.h"

namespace spindrift {

LiquidShadowPass::LiquidShadowPass(const ShaderLibrary& shaders)
    : lightProgram_(shaders.program({"fullscreen.vert", "liquid_shadow.frag"})),
      straightLightProgram_(
          shaders.program({"fullscreen.vert", "liquid_shadow.frag"}, {"TRANSMIT_STRAIGHT"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

void LiquidShadowPass::begin(int width, int height) {
  ensureTexture(shadowSum_, GL_RGBA32F, width, height);
  ensureTexture(lampDiffuse_, GL_RGBA32F, width, height);
  const float nothing[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  glClearTexImage(shadowSum_.id(), 0, GL_RGBA, GL_FLOAT, nothing);
  glClearTexImage(lampDiffuse_.id(), 0, GL_RGBA, GL_FLOAT, nothing);
}

void LiquidShadowPass::addLight(const Light& light, const SurfaceLayers& layers,
                                const BackgroundData& background, const LiquidParameters& parameters,
                                bool transmitStraight) {
  const GLuint program = transmitStraight ? straightLightProgram_.id() : lightProgram_.id();
  setLightUniforms(program, light);
  if (transmitStraight) {
    glProgramUniform1f(program, uniformLocation(program, "indexOfRefraction"), parameters.ior);
    const glm::vec3 absorption = parameters.absorption * parameters.absorption_rgb;
    glProgramUniform3fv(program, uniformLocation(program, "absorptionPerUnitLength"), 1, &absorption.x);
  }
  // Every light adds its weighted shadow and its weight, and the diffuse light it gives the point.
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  bindColorTargets(framebuffer_.id(), {&shadowSum_, &lampDiffuse_});
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program);
  glBindTextureUnit(0, background.eyeDepth.id());
  glBindTextureUnit(1, layers.front.eyeDepth.id());
  glBindTextureUnit(2, layers.back.eyeDepth.id());
  glBindTextureUnit(3, layers.front.normal.id());
  drawFullscreenTriangle(emptyVertexArray_.id());
  glDisable(GL_BLEND);
  checkGlError("shadowing the background");
}

}  // namespace spindrift
