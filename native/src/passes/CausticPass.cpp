#include "passes/CausticPass.h"

#include "passes/FrameUniforms.h"
#include "passes/LightUniforms.h"

namespace spindrift {

CausticPass::CausticPass(const ShaderLibrary& shaders)
    : pathsProgram_(shaders.program({"caustic_paths.comp"})),
      splatProgram_(shaders.program({"caustic_splat.vert", "caustic_splat.geom", "caustic_splat.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

void CausticPass::begin(int width, int height) {
  ensureTexture(causticSum_, GL_RGBA32F, width, height);
  const float nothing[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  glClearTexImage(causticSum_.id(), 0, GL_RGBA, GL_FLOAT, nothing);
  ensureTexture(causticTiles_, GL_R8UI, pixelTilesAcross(width), pixelTilesDown(height));
  const GLubyte none = 0;
  glClearTexImage(causticTiles_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &none);
}

void CausticPass::addLight(const Light& light, const SurfaceLayers& layers, const BackgroundData& background,
                           const LiquidParameters& liquid, const LightParameters& parameters) {
  const int lightSize = layers.front.eyeDepth.width;
  const int step = parameters.caustic_grid_step;
  const int grid = (lightSize - 1) / step + 1;
  ensureTexture(receiverPosition_, GL_RGBA32F, grid, grid);
  ensureTexture(receiverLight_, GL_RGBA32F, grid, grid);
  ensureTexture(receiverLightTexel_, GL_RGBA32F, grid, grid);

  const GLuint paths = pathsProgram_.id();
  glUseProgram(paths);
  setLightUniforms(paths, light);
  glUniform1i(uniformLocation(paths, "gridStep"), step);
  glUniform1f(uniformLocation(paths, "indexOfRefraction"), liquid.ior);
  const glm::vec3 absorption = liquid.absorption * liquid.absorption_rgb;
  glUniform3fv(uniformLocation(paths, "absorptionPerUnitLength"), 1, &absorption.x);
  glUniform1f(uniformLocation(paths, "stepPixels"), liquid.trace_step_pixels);
  glUniform1i(uniformLocation(paths, "maxSteps"), liquid.trace_max_steps);
  glBindTextureUnit(0, background.eyeDepth.id());
  glBindTextureUnit(1, layers.front.eyeDepth.id());
  glBindTextureUnit(2, layers.back.eyeDepth.id());
  glBindTextureUnit(3, layers.front.normal.id());
  glBindTextureUnit(4, layers.back.normal.id());
  glBindImageTexture(0, receiverPosition_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(1, receiverLight_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(2, receiverLightTexel_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glDispatchCompute(GLuint((grid + 7) / 8), GLuint((grid + 7) / 8), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  checkGlError("tracing light through the liquid");

  const GLuint splat = splatProgram_.id();
  bindColorTargets(framebuffer_.id(), {&causticSum_});
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glBlendEquation(GL_FUNC_ADD);
  glUseProgram(splat);
  setLightUniforms(splat, light);
  glUniform1i(uniformLocation(splat, "gridStep"), step);
  glUniform1f(uniformLocation(splat, "maxConcentration"), parameters.max_concentration);
  glBindTextureUnit(0, receiverPosition_.id());
  glBindTextureUnit(1, receiverLight_.id());
  glBindTextureUnit(2, receiverLightTexel_.id());
  glBindTextureUnit(3, background.eyeDepth.id());
  glBindImageTexture(3, causticTiles_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
  glBindVertexArray(emptyVertexArray_.id());
  glDrawArrays(GL_TRIANGLES, 0, GLsizei(grid - 1) * GLsizei(grid - 1) * 6);
  glDisable(GL_BLEND);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  checkGlError("splatting caustics");
}

}  // namespace spindrift
