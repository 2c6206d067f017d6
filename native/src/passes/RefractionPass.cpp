#include "passes/RefractionPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {
namespace {
// The shader's RayCounters buffer (refraction.frag says what each counts).
constexpr int kRayCounters = 9;
}  // namespace

RefractionPass::RefractionPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "refraction.frag"})),
      packProgram_(shaders.program({"fullscreen.vert", "refraction_layers.frag"})),
      packFramebuffer_(createFramebuffer()),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()),
      counters_(createCounters(kRayCounters)) {
  const float noSurface[4] = {1e10f, 0.0f, 0.0f, 0.0f};
  uploadTexture(emptyLayer_, GL_RGBA32F, 1, 1, 4, noSurface, false);
}

LiquidData RefractionPass::run(const std::optional<SurfaceLayers>& splashes,
                               const std::optional<SurfaceLayers>& aggregates,
                               const BackgroundData& background, const LiquidParameters& parameters,
                               bool cameraInLiquid, float particleRadius, const DomainBox* domain,
                               const PixelTiles* tiles, int width, int height) {
  ensureTexture(color_, GL_RGBA32F, width, height);
  ensureTexture(splashColor_, GL_RGBA32F, width, height);
  ensureTexture(surfaceClass_, GL_R32F, width, height);
  ensureTexture(thickness_, GL_R32F, width, height);
  ensureTexture(frontDepth_, GL_R32F, width, height);
  ensureTexture(frontNormal_, GL_RGBA16F, width, height);
  ensureTexture(refractionUv_, GL_RGBA32F, width, height);
  ensureTexture(transmittance_, GL_RGBA32F, width, height);
  ensureTexture(reflection_, GL_RGBA32F, width, height);
  glBindImageTexture(0, refractionUv_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(1, transmittance_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  glBindImageTexture(2, reflection_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  ensureTexture(layerDepths_, GL_RGBA32F, width, height);
  ensureTextureArray(layerNormals_, GL_RGBA16F, width, height, 4);
  if (tiles) clearToNoLiquid();  // the tiles not drawn keep these values
  packLayers(splashes, aggregates, tiles);

  const GLuint framebuffer = framebuffer_.id();
  const Texture2D* outputs[] = {&color_,     &splashColor_, &surfaceClass_,
                                &thickness_, &frontDepth_,  &frontNormal_};
  GLenum attachments[6];
  for (int i = 0; i < 6; ++i) {
    attachments[i] = GL_COLOR_ATTACHMENT0 + i;
    glNamedFramebufferTexture(framebuffer, attachments[i], outputs[i]->id(), 0);
  }
  glNamedFramebufferDrawBuffers(framebuffer, 6, attachments);

  const std::uint32_t zeros[kRayCounters] = {};
  glNamedBufferSubData(counters_.id(), 0, sizeof zeros, zeros);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counters_.id());

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = program_.id();
  glUseProgram(program);
  glBindTextureUnit(4, layerNormals_.id());
  glBindTextureUnit(8, background.color.id());
  glBindTextureUnit(9, background.eyeDepth.id());
  glBindTextureUnit(10, background.environment ? background.environment->id() : 0);
  glBindTextureUnit(11, layerDepths_.id());

  const glm::vec3 absorption = parameters.absorption * parameters.absorption_rgb;
  glUniform1i(uniformLocation(program, "hasSplash"), splashes ? 1 : 0);
  glUniform1i(uniformLocation(program, "hasAggregate"), aggregates ? 1 : 0);
  glUniform1i(uniformLocation(program, "hasEnvironment"), background.environment ? 1 : 0);
  glUniform3fv(uniformLocation(program, "fallbackColor"), 1, &background.fallbackColor.x);
  glUniform1f(uniformLocation(program, "indexOfRefraction"), parameters.ior);
  glUniform3fv(uniformLocation(program, "absorptionPerUnitLength"), 1, &absorption.x);
  glUniform1i(uniformLocation(program, "maxRefractions"), parameters.max_refractions);
  glUniform1i(uniformLocation(program, "maxInternalReflections"), parameters.internal_reflections);
  glUniform1i(uniformLocation(program, "cameraInLiquid"), cameraInLiquid ? 1 : 0);
  glUniform1f(uniformLocation(program, "solidContactDistance"), 2.0f * particleRadius);
  setDomainBoxUniforms(program, domain);
  glUniform1f(uniformLocation(program, "stepPixels"), parameters.trace_step_pixels);
  glUniform1f(uniformLocation(program, "reflectionStepPixels"), parameters.reflection_step_pixels);
  glUniform1i(uniformLocation(program, "maxSteps"), parameters.trace_max_steps);
  drawFullscreen(emptyVertexArray_.id(), tiles);
  // The image stores must land before the split layers are sampled or read back.
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                  GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  checkGlError("refracting through the liquid");
  return {color_,       splashColor_,  surfaceClass_,  thickness_, frontDepth_,
          frontNormal_, refractionUv_, transmittance_, reflection_};
}

void RefractionPass::packLayers(const std::optional<SurfaceLayers>& splashes,
                                const std::optional<SurfaceLayers>& aggregates, const PixelTiles* tiles) {
  auto layerTexture = [&](const std::optional<SurfaceLayers>& layers, bool back, bool normal) {
    if (!layers) return emptyLayer_.id();
    const DepthLayer& layer = back ? layers->back : layers->front;
    return normal ? layer.normal.id() : layer.eyeDepth.id();
  };
  // The marches' four depth reads per sample become one: the layers packed into one texel per pixel; and
  // the normals into one array texture.
  bindColorTargets(packFramebuffer_.id(), {&layerDepths_});
  const GLuint pack = packFramebuffer_.id();
  GLenum packAttachments[5] = {GL_COLOR_ATTACHMENT0};
  for (int layer = 0; layer < 4; ++layer) {
    packAttachments[layer + 1] = GL_COLOR_ATTACHMENT1 + GLenum(layer);
    glNamedFramebufferTextureLayer(pack, packAttachments[layer + 1], layerNormals_.id(), 0, layer);
  }
  glNamedFramebufferDrawBuffers(pack, 5, packAttachments);
  if (tiles) {  // the tiles not drawn keep no normal (clearToNoLiquid clears layerDepths_)
    const float noNormal[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (GLint drawBuffer = 1; drawBuffer < 5; ++drawBuffer)
      glClearNamedFramebufferfv(pack, GL_COLOR, drawBuffer, noNormal);
  }
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(packProgram_.id());
  for (GLuint body = 0; body < 2; ++body)
    for (GLuint back = 0; back < 2; ++back) {
      const std::optional<SurfaceLayers>& layers = body == 0 ? splashes : aggregates;
      glBindTextureUnit(body * 2 + back, layerTexture(layers, back == 1, false));
      glBindTextureUnit(4 + body * 2 + back, layerTexture(layers, back == 1, true));
    }
  drawFullscreen(emptyVertexArray_.id(), tiles);
  // The next pass to bind this framebuffer names its own attachments: leave none of the array's behind.
  for (int layer = 0; layer < 4; ++layer)
    glNamedFramebufferTexture(pack, GL_COLOR_ATTACHMENT1 + GLenum(layer), 0, 0);
  checkGlError("packing the depth layers for the refraction");
}

void RefractionPass::clearToNoLiquid() {
  // What refraction.frag and refraction_layers.frag write where no layer has a surface.
  const float zeros[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const float noSurface[4] = {1e10f, 1e10f, 1e10f, 1e10f};  // kNoSurfaceDepth
  clearColorTargets(packFramebuffer_.id(),
                    {&color_, &splashColor_, &surfaceClass_, &thickness_, &frontNormal_, &refractionUv_,
                     &transmittance_, &reflection_},
                    zeros);
  clearColorTargets(packFramebuffer_.id(), {&frontDepth_, &layerDepths_}, noSurface);
}

RefractionStatistics RefractionPass::statistics() const {
  std::uint32_t counters[kRayCounters] = {};
  readCounters(counters_, counters, kRayCounters);
  RefractionStatistics statistics;
  for (int i = 0; i < 4; ++i)
    statistics.orders[i] = counters[i];
  statistics.raysWithSecondBody = counters[4];
  statistics.totalInternalReflections = counters[5];
  statistics.liquidPixels = counters[6];
  statistics.exitsOffScreen = counters[7];
  statistics.exitsBehindSolids = counters[8];
  return statistics;
}

}  // namespace spindrift
