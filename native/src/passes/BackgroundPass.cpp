#include "passes/BackgroundPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {

BackgroundPass::BackgroundPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "background.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

void BackgroundPass::upload(const BackgroundImages& images) {
  if (images.generation == uploadedGeneration_) return;
  auto uploadOrRelease = [](Texture2D& texture, const FloatImage* image, GLenum format, bool linear) {
    if (image)
      uploadTexture(texture, format, image->width, image->height, image->channels, image->pixels.data(),
                    linear);
    else
      texture = Texture2D{};
  };
  uploadOrRelease(imageTexture_, images.color, GL_RGBA32F, false);
  uploadOrRelease(depthTexture_, images.eyeDepth, GL_R32F, false);
  uploadOrRelease(environmentTexture_, images.environment, GL_RGBA32F, true);
  uploadOrRelease(liquidDepthTexture_, images.liquidEyeDepth, GL_R32F, false);
  for (int i = 0; i < 3; ++i)
    uploadOrRelease(lightPassTextures_[i], images.lightPasses ? &(*images.lightPasses)[i] : nullptr,
                    GL_RGBA32F, false);
  if (environmentTexture_) glTextureParameteri(environmentTexture_.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
  uploadedGeneration_ = images.generation;
}

BackgroundData BackgroundPass::run(const BackgroundImages& images, int width, int height) {
  upload(images);
  ensureTexture(color_, GL_RGBA32F, width, height);
  ensureTexture(eyeDepth_, GL_R32F, width, height);
  glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, color_.id(), 0);
  glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT1, eyeDepth_.id(), 0);
  const GLenum attachments[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer_.id(), 2, attachments);

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(program_.id());
  glUniform1i(uniformLocation(program_.id(), "hasImage"), imageTexture_ ? 1 : 0);
  glUniform1i(uniformLocation(program_.id(), "hasDepth"), depthTexture_ ? 1 : 0);
  glUniform1i(uniformLocation(program_.id(), "hasEnvironment"), environmentTexture_ ? 1 : 0);
  glUniform3fv(uniformLocation(program_.id(), "backgroundColor"), 1, &images.fallbackColor.x);
  glBindTextureUnit(0, imageTexture_.id());
  glBindTextureUnit(1, depthTexture_.id());
  glBindTextureUnit(2, environmentTexture_.id());
  drawFullscreenTriangle(emptyVertexArray_.id());
  checkGlError("resolving the background");
  return {color_,
          eyeDepth_,
          environmentTexture_ ? &environmentTexture_ : nullptr,
          images.fallbackColor,
          liquidDepthTexture_ ? &liquidDepthTexture_ : nullptr,
          lightPassTextures_[0] ? lightPassTextures_ : nullptr};
}

}  // namespace spindrift
