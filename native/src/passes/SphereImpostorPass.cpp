#include "passes/SphereImpostorPass.h"

#include "spindrift/Error.h"

namespace spindrift {

SphereImpostorPass::SphereImpostorPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"sphere_impostor.vert", "sphere_impostor.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()),
      sphereBuffer_(createBuffer()) {}

SurfaceData SphereImpostorPass::run(const std::vector<glm::vec4>& spheres, const BackgroundData& background,
                                    int width, int height) {
  ensureTexture(eyeDepth_, GL_R32F, width, height);
  ensureTexture(normal_, GL_RGBA16F, width, height);
  ensureTexture(depthBuffer_, GL_DEPTH_COMPONENT32F, width, height);
  glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, eyeDepth_.id(), 0);
  glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT1, normal_.id(), 0);
  glNamedFramebufferTexture(framebuffer_.id(), GL_DEPTH_ATTACHMENT, depthBuffer_.id(), 0);
  const GLenum attachments[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer_.id(), 2, attachments);

  const float noSurface[4] = {1e10f, 0.0f, 0.0f, 0.0f};
  const float noNormal[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const float farthest = 1.0f;
  glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, noSurface);
  glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 1, noNormal);
  glClearNamedFramebufferfv(framebuffer_.id(), GL_DEPTH, 0, &farthest);
  if (spheres.empty()) return {eyeDepth_, normal_};

  // Grow-only storage: a sequence of frames reallocates only when a frame has more spheres than any before.
  const std::size_t bytes = spheres.size() * sizeof(glm::vec4);
  if (bytes > sphereBufferBytes_) {
    sphereBuffer_ = createBuffer();
    glNamedBufferStorage(sphereBuffer_.id(), GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    sphereBufferBytes_ = bytes;
  }
  glNamedBufferSubData(sphereBuffer_.id(), 0, GLsizeiptr(bytes), spheres.data());
  checkGlError("uploading particles");

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glUseProgram(program_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, sphereBuffer_.id());
  glBindTextureUnit(0, background.eyeDepth.id());
  glBindVertexArray(emptyVertexArray_.id());
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(spheres.size()));
  glDisable(GL_DEPTH_TEST);
  checkGlError("drawing sphere impostors");
  return {eyeDepth_, normal_};
}

}  // namespace spindrift
