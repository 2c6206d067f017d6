#include "passes/FoamIntensityPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {

FoamIntensityPass::FoamIntensityPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "foam_intensity.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

FoamIntensityData FoamIntensityPass::run(const FoamThicknessData& thickness, const FoamParameters& parameters,
                                         int width, int height) {
  ensureTexture(intensity_, GL_R32F, width, height);
  bindColorTargets(framebuffer_.id(), {&intensity_});
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = program_.id();
  glUseProgram(program);
  glUniform1f(uniformLocation(program, "intensityMod"), parameters.intensity_mod);
  glUniform1f(uniformLocation(program, "intensityExp"), parameters.intensity_exp);
  glBindTextureUnit(0, thickness.thickness.id());
  drawFullscreenTriangle(emptyVertexArray_.id());
  checkGlError("converting foam thickness to intensity");
  return {intensity_};
}

}  // namespace spindrift
