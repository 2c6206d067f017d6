#include "passes/NormalsFromDepthPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {

NormalsFromDepthPass::NormalsFromDepthPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "depth_normals.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

RecomputedNormals NormalsFromDepthPass::run(const Texture2D& smoothedEyeDepth,
                                            const Texture2D& originalNormal, bool backLayer,
                                            const PixelTiles* tiles, int width, int height) {
  ensureTexture(normal_, GL_RGBA16F, width, height);
  const float noNormal[4] = {0.0f, 0.0f, 0.0f, 0.0f};  // what depth_normals.frag writes off the surface
  if (tiles) clearColorTargets(framebuffer_.id(), {&normal_}, noNormal);
  glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, normal_.id(), 0);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = program_.id();
  glUseProgram(program);
  glUniform1i(uniformLocation(program, "backLayer"), backLayer ? 1 : 0);
  glBindTextureUnit(0, smoothedEyeDepth.id());
  glBindTextureUnit(1, originalNormal.id());
  drawFullscreen(emptyVertexArray_.id(), tiles);
  checkGlError("recomputing normals from depth");
  return {normal_};
}

}  // namespace spindrift
