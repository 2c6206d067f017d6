#include "passes/PixelTilePass.h"

#include "spindrift/Error.h"

namespace spindrift {

PixelTilePass::PixelTilePass(const ShaderLibrary& shaders)
    : program_(shaders.program({"pixel_tiles.comp"})), counter_(createCounters(1)) {}

PixelTiles PixelTilePass::run(const std::vector<const Texture2D*>& eyeDepths, int width, int height) {
  if (eyeDepths.size() == 0 || eyeDepths.size() > 4) throw Error("PixelTilePass: one to four layers");
  const int tilesX = pixelTilesAcross(width), tilesY = pixelTilesDown(height);
  ensureTexture(marked_, GL_R8UI, tilesX, tilesY);
  const std::uint32_t zero = 0;
  glNamedBufferSubData(counter_.id(), 0, sizeof zero, &zero);
  const GLuint program = program_.id();
  glUseProgram(program);
  glUniform1i(uniformLocation(program, "layerCount"), GLint(eyeDepths.size()));
  GLuint unit = 0;
  for (const Texture2D* eyeDepth : eyeDepths)
    glBindTextureUnit(unit++, eyeDepth->id());
  glBindImageTexture(0, marked_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counter_.id());
  glDispatchCompute(GLuint((tilesX + 7) / 8), GLuint((tilesY + 7) / 8), 1);  // 8 × 8 tiles a work group
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  checkGlError("marking the pixel tiles that hold liquid");
  return {marked_};
}

std::uint32_t PixelTilePass::markedTiles() const {
  std::uint32_t count = 0;
  readCounters(counter_, &count, 1);
  return count;
}

}  // namespace spindrift
