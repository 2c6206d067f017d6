#include "passes/RimNormalsPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {

RimNormalsPass::RimNormalsPass(const ShaderLibrary& shaders)
    : edgeRowsProgram_(shaders.program({"fullscreen.vert", "rim_edge_rows.frag"})),
      normalsProgram_(shaders.program({"fullscreen.vert", "rim_normals.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

RecomputedNormals RimNormalsPass::run(const SurfaceLayers& body, const Texture2D& solidEyeDepth,
                                      const DomainBox* domain, float particleRadius, const PixelTiles* tiles,
                                      int width, int height) {
  ensureTexture(edgeRows_, GL_R16F, width, height);
  ensureTexture(normal_, GL_RGBA16F, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  // Both targets hold 0 where the tiles leave them: a tile without the layer is uncovered throughout, so each
  // of its pixels is its own row's nearest uncovered pixel (offset 0), and has no normal.
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const auto drawInto = [&](const Texture2D& target) {
    if (tiles)
      clearColorTargets(framebuffer_.id(), {&target}, zero);
    else
      bindColorTargets(framebuffer_.id(), {&target});
  };
  drawInto(edgeRows_);
  glUseProgram(edgeRowsProgram_.id());
  glBindTextureUnit(0, body.front.eyeDepth.id());
  drawFullscreen(emptyVertexArray_.id(), tiles);

  drawInto(normal_);
  const GLuint program = normalsProgram_.id();
  glUseProgram(program);
  setDomainBoxUniforms(program, domain);
  glUniform1f(uniformLocation(program, "particleRadius"), particleRadius);
  glBindTextureUnit(0, body.front.eyeDepth.id());
  glBindTextureUnit(1, body.front.normal.id());
  glBindTextureUnit(2, body.back.eyeDepth.id());
  glBindTextureUnit(3, solidEyeDepth.id());
  glBindTextureUnit(4, edgeRows_.id());
  drawFullscreen(emptyVertexArray_.id(), tiles);
  checkGlError("bending the rim's normals");
  return {normal_};
}

}  // namespace spindrift
