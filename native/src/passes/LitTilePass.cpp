#include "passes/LitTilePass.h"

namespace spindrift {

LitTilePass::LitTilePass(const ShaderLibrary& shaders)
    : program_(shaders.program({"lit_tiles.comp"})),
      shadowingProgram_(shaders.program({"lit_tiles.comp"}, {"SHADOW_IN_PLACE"})),
      counter_(createCounters(1)) {}

LitTiles LitTilePass::run(const BackgroundData& background, const LampLight& lamps,
                          const CausticData& caustics, const SkyOcclusionData& sky, int width, int height) {
  const int tilesX = pixelTilesAcross(width), tilesY = pixelTilesDown(height);
  ensureTexture(lit_, GL_R8UI, tilesX, tilesY);
  ensureTexture(plain_, GL_R8UI, tilesX, tilesY);
  const std::uint32_t zero = 0;
  glNamedBufferSubData(counter_.id(), 0, sizeof zero, &zero);
  const GLuint program = lamps.light ? shadowingProgram_.id() : program_.id();
  glUseProgram(program);
  glUniform1i(uniformLocation(program, "skyOcclusionScale"), sky.scale);
  glBindTextureUnit(2, caustics.tiles.id());
  glBindTextureUnit(3, background.eyeDepth.id());
  glBindTextureUnit(10, sky.kept.id());
  if (lamps.light) {
    glBindTextureUnit(8, lamps.layers->front.eyeDepth.id());
    glBindTextureUnit(9, lamps.layers->back.eyeDepth.id());
  } else {
    glBindTextureUnit(1, lamps.sums->shadowSum.id());
  }
  glBindImageTexture(0, lit_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
  glBindImageTexture(1, plain_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counter_.id());
  glDispatchCompute(GLuint((tilesX + 7) / 8), GLuint((tilesY + 7) / 8), 1);  // 8 × 8 tiles a work group
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  checkGlError("marking the pixel tiles the lights change");
  return {PixelTiles{lit_}, PixelTiles{plain_}};
}

std::uint32_t LitTilePass::litTiles() const {
  std::uint32_t count = 0;
  readCounters(counter_, &count, 1);
  return count;
}

}  // namespace spindrift
