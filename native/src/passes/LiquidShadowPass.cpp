#include "passes/LiquidShadowPass.h"

#include "passes/FrameUniforms.h"
#include "passes/LightUniforms.h"

namespace spindrift {

LiquidShadowPass::LiquidShadowPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "liquid_shadow.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

void LiquidShadowPass::begin(int width, int height) {
  ensureTexture(shadowSum_, GL_RGBA32F, width, height);
  ensureTexture(skyKept_, GL_RGBA32F, width, height);
  ensureTexture(lampDiffuse_, GL_RGBA32F, width, height);
  const float nothing[4] = {0.0f, 0.0f, 0.0f, 0.0f}, everything[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  glClearTexImage(shadowSum_.id(), 0, GL_RGBA, GL_FLOAT, nothing);
  glClearTexImage(lampDiffuse_.id(), 0, GL_RGBA, GL_FLOAT, nothing);
  glClearTexImage(skyKept_.id(), 0, GL_RGBA, GL_FLOAT, everything);
}

void LiquidShadowPass::addLight(const Light& light, const SurfaceLayers& layers,
                                const BackgroundData& background, const LiquidParameters& parameters,
                                bool transmitStraight) {
  setLightUniforms(program_.id(), light);
  // Every light adds its weighted shadow and its weight, and the diffuse light it gives the point.
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  bindColorTargets(framebuffer_.id(), {&shadowSum_, &lampDiffuse_});
  draw(layers, background, parameters, false, transmitStraight);
  glDisable(GL_BLEND);
}

void LiquidShadowPass::setSky(const SurfaceLayers& layers, const BackgroundData& background,
                              const LiquidParameters& parameters, float particleRadius,
                              const SkyOcclusionData* occlusion) {
  glProgramUniform1f(program_.id(), uniformLocation(program_.id(), "submergedTolerance"),
                     2.0f * particleRadius);
  glProgramUniform1i(program_.id(), uniformLocation(program_.id(), "skyOcclusionScale"),
                     occlusion ? occlusion->scale : 0);
  glBindTextureUnit(4, occlusion ? occlusion->kept.id() : 0);
  bindColorTargets(framebuffer_.id(), {&skyKept_});
  draw(layers, background, parameters, true, true);
}

void LiquidShadowPass::draw(const SurfaceLayers& layers, const BackgroundData& background,
                            const LiquidParameters& parameters, bool sky, bool transmitStraight) {
  const GLuint program = program_.id();
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program);
  glUniform1i(uniformLocation(program, "skyMode"), sky ? 1 : 0);
  glUniform1i(uniformLocation(program, "transmitStraight"), transmitStraight ? 1 : 0);
  glUniform1f(uniformLocation(program, "indexOfRefraction"), parameters.ior);
  const glm::vec3 absorption = parameters.absorption * parameters.absorption_rgb;
  glUniform3fv(uniformLocation(program, "absorptionPerUnitLength"), 1, &absorption.x);
  glBindTextureUnit(0, background.eyeDepth.id());
  glBindTextureUnit(1, layers.front.eyeDepth.id());
  glBindTextureUnit(2, layers.back.eyeDepth.id());
  glBindTextureUnit(3, layers.front.normal.id());
  drawFullscreenTriangle(emptyVertexArray_.id());
  checkGlError(sky ? "finding submerged points" : "shadowing the background");
}

}  // namespace spindrift
