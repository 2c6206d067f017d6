#include "passes/FoamDepthPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {

FoamDepthPass::FoamDepthPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"foam_sprite.vert", "foam_depth.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()),
      particleBuffer_(createBuffer()) {}

FoamSurfaceData FoamDepthPass::run(const std::vector<FoamInstance>& particles, const FoamSceneDepth& scene,
                                   int width, int height) {
  // Grow-only storage: a sequence reallocates only when a frame has more foam in view than any before it.
  const std::size_t bytes = particles.size() * sizeof(FoamInstance);
  if (bytes > particleBufferBytes_) {
    particleBuffer_ = createBuffer();
    glNamedBufferStorage(particleBuffer_.id(), GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    particleBufferBytes_ = bytes;
  }
  if (bytes > 0) glNamedBufferSubData(particleBuffer_.id(), 0, GLsizeiptr(bytes), particles.data());
  checkGlError("uploading foam particles");

  ensureTexture(depthAndSearchRadius_, GL_RG32F, width, height);
  ensureTexture(normal_, GL_RGBA16F, width, height);
  ensureTexture(depthBuffer_, GL_DEPTH_COMPONENT32F, width, height);
  const GLuint framebuffer = framebuffer_.id();
  glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depthBuffer_.id(), 0);
  bindColorTargets(framebuffer, {&depthAndSearchRadius_, &normal_});
  const float noSurface[4] = {1e10f, 0.0f, 0.0f, 0.0f};
  const float noNormal[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const float farthest = 1.0f;
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, noSurface);
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 1, noNormal);
  glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &farthest);

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glUseProgram(program_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, particleBuffer_.id());
  glBindTextureUnit(0, scene.solidEyeDepth.id());
  glBindVertexArray(emptyVertexArray_.id());
  glDrawArrays(GL_TRIANGLES, 0, GLsizei(3 * particles.size()));
  glDisable(GL_DEPTH_TEST);
  // Submitted at once: issued behind it unsubmitted, llvmpipe ran the thickness pass's sprites 3-5 times
  // slower (the drop's steady frame 431-510 against 304-321 ms; docs/frame-cost.md, session 45).
  glFlush();
  checkGlError("drawing foam depth");
  return {depthAndSearchRadius_, normal_, particleBuffer_, GLsizei(particles.size())};
}

}  // namespace spindrift
