#include "passes/SkyOcclusionPass.h"

#include <cmath>

#include "passes/FrameUniforms.h"

namespace spindrift {

SkyOcclusionPass::SkyOcclusionPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "sky_occlusion.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

SkyOcclusionData SkyOcclusionPass::run(const SurfaceLayers& skyLayers, const LightView& sky,
                                       const LiquidBounds& bounds, const BackgroundData& background,
                                       const Parameters& parameters, int scale, int width, int height) {
  ensureTexture(kept_, GL_RGBA32F, (width + scale - 1) / scale, (height + scale - 1) / scale);
  bindColorTargets(framebuffer_.id(), {&kept_});
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = program_.id();
  glUseProgram(program);
  const LiquidParameters& liquid = parameters.liquid;
  glUniform1i(uniformLocation(program, "scale"), scale);
  glUniform1i(uniformLocation(program, "directionCount"), parameters.light.sky_occlusion_directions);
  glUniform4f(uniformLocation(program, "liquidBounds"), bounds.centre.x, bounds.centre.y, bounds.centre.z,
              bounds.radius);
  glUniform3fv(uniformLocation(program, "liquidBoxLow"), 1, &bounds.low.x);
  glUniform3fv(uniformLocation(program, "liquidBoxHigh"), 1, &bounds.high.x);
  glUniform1f(uniformLocation(program, "skyTexel"), sky.texelSize);
  // Steps of one texel and of two found the same light kept (the light benchmark's errors to four digits) at
  // three quarters of the pass's time for the pool from above.
  glUniform1f(uniformLocation(program, "shortestStep"), 2.0f * sky.texelSize);
  // As lib/submerged_sky.glsl: the drawn bottom undulates by about a particle radius.
  glUniform1f(uniformLocation(program, "submergedTolerance"), 2.0f * bounds.particleRadius);
  // A tank's wall or a floor is thicker than this; a point that far behind what the camera sees is taken as
  // hidden from it rather than inside a solid.
  glUniform1f(uniformLocation(program, "solidThickness"), 4.0f * bounds.particleRadius);
  const glm::vec3 absorption = liquid.absorption * liquid.absorption_rgb;
  glUniform3fv(uniformLocation(program, "absorptionPerUnitLength"), 1, &absorption.x);
  glUniform1f(uniformLocation(program, "windowCosine"), std::sqrt(1.0f - 1.0f / (liquid.ior * liquid.ior)));
  glBindTextureUnit(0, background.eyeDepth.id());
  glBindTextureUnit(1, skyLayers.front.eyeDepth.id());
  glBindTextureUnit(2, skyLayers.back.eyeDepth.id());
  drawFullscreenTriangle(emptyVertexArray_.id());
  checkGlError("occluding the sky");
  return {kept_, scale};
}

}  // namespace spindrift
