#include "passes/LitBackgroundPass.h"

#include "passes/FrameUniforms.h"
#include "passes/LightUniforms.h"

namespace spindrift {

LitBackgroundPass::LitBackgroundPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "lit_background.frag"})),
      upsamplingProgram_(
          shaders.program({"fullscreen.vert", "lit_background.frag"}, {"SKY_OCCLUSION_SAMPLES"})),
      shadowingProgram_(shaders.program({"fullscreen.vert", "lit_background.frag"},
                                        {"SKY_OCCLUSION_SAMPLES", "SHADOW_IN_PLACE"})),
      plainProgram_(shaders.program({"fullscreen.vert", "lit_background.frag"}, {"PLAIN"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

LitBackgroundData LitBackgroundPass::run(const BackgroundData& background, const LampLight& lamps,
                                         const CausticData& caustics, const SkyView& sky,
                                         const Parameters& parameters, const LitTiles* tiles, int width,
                                         int height) {
  for (Texture2D* target : {&color_, &liquidShadow_, &caustics_, &skyKept_})
    ensureTexture(*target, GL_RGBA32F, width, height);
  if (tiles) {
    // What the full variant writes where no light changes the background: all of the lamps' and the sky's
    // light kept, no caustics. The tiles it shades overwrite these; PLAIN writes the others' colour.
    const float kept[4] = {1.0f, 1.0f, 1.0f, 1.0f}, none[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    clearColorTargets(framebuffer_.id(), {&liquidShadow_, &skyKept_}, kept);
    clearColorTargets(framebuffer_.id(), {&caustics_}, none);
  }
  bindColorTargets(framebuffer_.id(), {&color_, &liquidShadow_, &caustics_, &skyKept_});
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = lamps.light     ? shadowingProgram_.id()
                         : sky.occlusion ? upsamplingProgram_.id()
                                         : program_.id();
  glUseProgram(program);
  const bool hasLightPasses = background.lightPasses != nullptr;
  glUniform1i(uniformLocation(program, "hasLightPasses"), hasLightPasses ? 1 : 0);
  // Without a lamp none of the background's light comes from one (light.sky_without_lamps).
  glUniform1f(uniformLocation(program, "directFraction"),
              lamps.none ? 0.0f : parameters.light.direct_fraction);
  glUniform1i(uniformLocation(program, "worldAlone"), lamps.none ? 1 : 0);
  if (sky.occlusion) {
    glUniform1i(uniformLocation(program, "skyOcclusionScale"), sky.occlusion->scale);
    glBindTextureUnit(10, sky.occlusion->kept.id());
  } else {
    const glm::vec3 absorption = parameters.liquid.absorption * parameters.liquid.absorption_rgb;
    glUniform3fv(uniformLocation(program, "absorptionPerUnitLength"), 1, &absorption.x);
    glUniform1f(uniformLocation(program, "submergedTolerance"), 2.0f * sky.particleRadius);
    glBindTextureUnit(8, sky.layers.front.eyeDepth.id());
    glBindTextureUnit(9, sky.layers.back.eyeDepth.id());
  }
  glBindTextureUnit(0, background.color.id());
  if (lamps.light) {
    setLightUniforms(program, *lamps.light);
    glBindTextureUnit(8, lamps.layers->front.eyeDepth.id());
    glBindTextureUnit(9, lamps.layers->back.eyeDepth.id());
    glBindTextureUnit(11, lamps.layers->front.normal.id());
  } else {
    glBindTextureUnit(1, lamps.sums->shadowSum.id());
    glBindTextureUnit(7, lamps.sums->lampDiffuse.id());
  }
  glBindTextureUnit(2, caustics.causticSum.id());
  glBindTextureUnit(3, background.eyeDepth.id());
  for (int i = 0; i < 3; ++i)
    glBindTextureUnit(GLuint(4 + i), hasLightPasses ? background.lightPasses[i].id() : 0);
  drawFullscreen(emptyVertexArray_.id(), tiles ? &tiles->lit : nullptr);
  if (tiles) {
    // The background as it is (lit_background.frag, PLAIN), into the colour alone.
    bindColorTargets(framebuffer_.id(), {&color_});
    const GLuint plain = plainProgram_.id();
    glUseProgram(plain);
    glUniform1i(uniformLocation(plain, "hasLightPasses"), hasLightPasses ? 1 : 0);
    drawFullscreen(emptyVertexArray_.id(), &tiles->plain);
  }
  checkGlError("lighting the background");
  return {BackgroundData{color_, background.eyeDepth, background.environment, background.fallbackColor,
                         background.liquidEyeDepth, background.lightPasses},
          liquidShadow_, caustics_, skyKept_};
}

}  // namespace spindrift
