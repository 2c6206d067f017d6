#include "passes/FoamVisibilityPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {

FoamVisibilityPass::FoamVisibilityPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"fullscreen.vert", "foam_visibility.frag"})),
      emptyVertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {}

FoamVisibilityTiles FoamVisibilityPass::run(const FoamSceneDepth& scene, const FoamParameters& parameters,
                                            int width, int height) {
  FoamVisibilityTiles tiles;
  tiles.tileSize = kTileSize;
  tiles.columns = (width + kTileSize - 1) / kTileSize;
  tiles.rows = (height + kTileSize - 1) / kTileSize;
  ensureTexture(hiddenBeyondTiles_, GL_RG32F, tiles.columns, tiles.rows);
  bindColorTargets(framebuffer_.id(), {&hiddenBeyondTiles_});
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const GLuint program = program_.id();
  glUseProgram(program);
  glUniform1i(uniformLocation(program, "tileSize"), kTileSize);
  glUniform1f(uniformLocation(program, "attenuationDistance"), parameters.attenuation_distance);
  glBindTextureUnit(0, scene.solidEyeDepth.id());
  glBindTextureUnit(1, scene.fluidEyeDepth.id());
  drawFullscreenTriangle(emptyVertexArray_.id());
  tiles.hiddenBeyond.resize(std::size_t(tiles.columns) * tiles.rows);
  glGetTextureImage(hiddenBeyondTiles_.id(), 0, GL_RG, GL_FLOAT,
                    GLsizei(tiles.hiddenBeyond.size() * sizeof(glm::vec2)), tiles.hiddenBeyond.data());
  checkGlError("finding where foam can be seen");
  return tiles;
}

}  // namespace spindrift
