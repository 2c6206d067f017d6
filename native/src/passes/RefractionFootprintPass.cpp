#include "passes/RefractionFootprintPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {
namespace {
// The width of a box with the spread of Cycles' Blackman-Harris pixel filter of width 1: Cycles draws the
// window over twice the width it is given (scene/film.cpp), and the window's standard deviation is 0.1385 of
// its span, a box's 1 / sqrt(12) of its width: 2 * 0.1385 * sqrt(12).
constexpr float kBlackmanHarrisAsBox = 0.96f;
}  // namespace

RefractionFootprintPass::RefractionFootprintPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "refraction_footprint.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

void RefractionFootprintPass::run(const LiquidData& liquid, const BackgroundData& background,
                                  float pixelFilterWidth, const PixelTiles* tiles) {
  // The shader discards the pixels a footprint adds nothing to: they keep the refraction's colour.
  bindColorTargets(framebuffer_.id(), {&liquid.color, &liquid.splashColor});
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = program_.id();
  glUseProgram(program);
  glBindTextureUnit(0, liquid.refractionUv.id());
  glBindTextureUnit(1, liquid.transmittance.id());
  glBindTextureUnit(2, liquid.reflection.id());
  glBindTextureUnit(3, liquid.surfaceClass.id());
  glBindTextureUnit(4, background.color.id());
  glBindTextureUnit(5, background.eyeDepth.id());
  glUniform1f(uniformLocation(program, "pixelFilterWidth"), pixelFilterWidth * kBlackmanHarrisAsBox);
  drawFullscreen(emptyVertexArray_.id(), tiles);
  checkGlError("averaging the background over the liquid's footprints");
}

}  // namespace spindrift
