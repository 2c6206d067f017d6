#include "passes/FoamSceneDepthPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {

FoamSceneDepthPass::FoamSceneDepthPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "foam_scene_depth.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

FoamSceneDepth FoamSceneDepthPass::run(const BackgroundData& background, const Texture2D* liquidFrontDepth,
                                       int width, int height) {
  ensureTexture(fluidEyeDepth_, GL_R32F, width, height);
  bindColorTargets(framebuffer_.id(), {&fluidEyeDepth_});
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = program_.id();
  glUseProgram(program);
  glBindTextureUnit(0, background.eyeDepth.id());
  glBindTextureUnit(1, liquidFrontDepth ? liquidFrontDepth->id() : 0);
  glBindTextureUnit(2, background.liquidEyeDepth ? background.liquidEyeDepth->id() : 0);
  glUniform1i(uniformLocation(program, "hasLiquidFront"), liquidFrontDepth ? 1 : 0);
  glUniform1i(uniformLocation(program, "hasRenderedLiquid"), background.liquidEyeDepth ? 1 : 0);
  drawFullscreenTriangle(emptyVertexArray_.id());
  checkGlError("resolving the depths foam is composited against");
  return {background.eyeDepth, fluidEyeDepth_};
}

}  // namespace spindrift
