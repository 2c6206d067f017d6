#include "passes/FoamBlurPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {

FoamBlurPass::FoamBlurPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "foam_blur.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

FoamLayerData FoamBlurPass::run(const FoamSurfaceData& surface, const FoamThicknessData& thickness,
                                const FoamIntensityData& intensity, const FoamOcclusionData& occlusion,
                                const FoamParameters& parameters, const PixelTiles* tiles, int width,
                                int height) {
  ensureTexture(horizontalShadow_, GL_R32F, width, height);
  ensureTexture(horizontalIrradiance_, GL_RGBA16F, width, height);
  for (Texture2D* layer : {&foam_, &spray_, &surface_, &bubble_})
    ensureTexture(*layer, GL_RGBA32F, width, height);
  ensureTexture(shadow_, GL_RGBA16F, width, height);
  ensureTexture(irradiance_, GL_RGBA16F, width, height);

  if (tiles) {  // what foam_blur.frag writes where there is no foam
    const float zeros[4] = {0.0f, 0.0f, 0.0f, 0.0f}, opaqueBlack[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    clearColorTargets(framebuffer_.id(), {&horizontalShadow_, &foam_, &spray_, &surface_, &bubble_}, zeros);
    clearColorTargets(framebuffer_.id(), {&horizontalIrradiance_, &shadow_, &irradiance_}, opaqueBlack);
  }
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = program_.id();
  glUseProgram(program);
  glUniform1f(uniformLocation(program, "blurRadiusFactor"), parameters.blur_radius_factor);
  glUniform1f(uniformLocation(program, "initialRadiusFactor"), parameters.ao_initial_radius_factor);
  glUniform3fv(uniformLocation(program, "shadowColor"), 1, &parameters.shadow_color.x);
  glUniform1f(uniformLocation(program, "irradianceScale"), parameters.irradiance_scale);
  glBindTextureUnit(2, surface.depthAndSearchRadius.id());
  glBindTextureUnit(3, intensity.intensity.id());
  glBindTextureUnit(4, thickness.thickness.id());

  // Horizontal, into the intermediate textures.
  bindColorTargets(framebuffer_.id(), {&horizontalShadow_, &horizontalIrradiance_});
  glUniform2i(uniformLocation(program, "direction"), 1, 0);
  glUniform1i(uniformLocation(program, "finalRun"), 0);
  glBindTextureUnit(0, occlusion.shadow.id());
  glBindTextureUnit(1, occlusion.irradiance.id());
  drawFullscreen(emptyVertexArray_.id(), tiles);

  // Vertical, into the foam layers.
  bindColorTargets(framebuffer_.id(),
                   {nullptr, nullptr, &foam_, &spray_, &surface_, &bubble_, &shadow_, &irradiance_});
  glUniform2i(uniformLocation(program, "direction"), 0, 1);
  glUniform1i(uniformLocation(program, "finalRun"), 1);
  glBindTextureUnit(0, horizontalShadow_.id());
  glBindTextureUnit(1, horizontalIrradiance_.id());
  drawFullscreen(emptyVertexArray_.id(), tiles);
  checkGlError("blurring and compositing the foam");
  return {foam_, spray_, surface_, bubble_, shadow_, irradiance_, thickness.thickness};
}

}  // namespace spindrift
