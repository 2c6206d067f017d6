#include "passes/FoamThicknessPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {

FoamThicknessPass::FoamThicknessPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"foam_sprite.vert", "foam_thickness.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

FoamThicknessData FoamThicknessPass::run(const FoamSurfaceData& surface, const FoamSceneDepth& scene,
                                         const FoamParameters& parameters, int width, int height) {
  ensureTexture(thickness_, GL_RGBA32F, width, height);
  bindColorTargets(framebuffer_.id(), {&thickness_});
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, zero);

  // Depth test and writes off: every fragment adds, not only the nearest (paper 2.2).
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFunc(GL_ONE, GL_ONE);
  const GLuint program = program_.id();
  glUseProgram(program);
  const FoamParameters& p = parameters;
  glUniform3f(uniformLocation(program, "falloffN"), p.spray_falloff_n, p.surface_falloff_n,
              p.bubble_falloff_n);
  glUniform3f(uniformLocation(program, "falloffM"), p.spray_falloff_m, p.surface_falloff_m,
              p.bubble_falloff_m);
  glUniform2f(uniformLocation(program, "lifetimeFalloff"), p.lifetime_falloff_n, p.lifetime_falloff_m);
  glUniform3f(uniformLocation(program, "attenuation"), p.attenuation_distance, p.attenuation_n,
              p.attenuation_m);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, surface.particles.id());
  glBindTextureUnit(0, scene.solidEyeDepth.id());
  glBindTextureUnit(1, scene.fluidEyeDepth.id());
  glBindVertexArray(emptyVertexArray_.id());
  glDrawArrays(GL_TRIANGLES, 0, 3 * surface.count);
  glDisable(GL_BLEND);
  checkGlError("accumulating foam thickness");
  return {thickness_};
}

}  // namespace spindrift
