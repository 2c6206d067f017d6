#include "passes/RaymarchTilePass.h"

#include <algorithm>

namespace spindrift {

int raymarchTileSize(const LiquidParameters& parameters) {
  return (std::max(parameters.raymarch_tile_size, 4) + 3) / 4 * 4;
}

RaymarchTilePass::RaymarchTilePass(const ShaderLibrary& shaders)
    : program_(shaders.program({"raymarch_tiles.comp"})), histogram_(createBuffer()) {
  glNamedBufferStorage(histogram_.id(), sizeof(TileHistogram), nullptr, GL_DYNAMIC_STORAGE_BIT);
}

RaymarchTileData RaymarchTilePass::run(const RaymarchEntryData& entry, float particleRadius,
                                       const LiquidParameters& parameters, int width, int height) {
  const int tileSize = raymarchTileSize(parameters);
  const int tilesX = (width + tileSize - 1) / tileSize, tilesY = (height + tileSize - 1) / tileSize;
  ensureTexture(levels_, GL_R8UI, tilesX, tilesY);
  const TileHistogram zeros{};
  glNamedBufferSubData(histogram_.id(), 0, sizeof zeros, zeros.data());
  const GLuint program = program_.id();
  glUseProgram(program);
  const std::string& resolution = parameters.raymarch_resolution;
  const int forcedLevel = resolution == "full"      ? 0
                          : resolution == "half"    ? 1
                          : resolution == "quarter" ? 2
                                                    : -1;
  const float squaredRadius = particleRadius * particleRadius;
  const float low = parameters.raymarch_variance_low, high = std::max(low, parameters.raymarch_variance_high);
  glUniform1i(uniformLocation(program, "tileSize"), tileSize);
  glUniform1f(uniformLocation(program, "varianceLow"), low * squaredRadius);
  glUniform1f(uniformLocation(program, "varianceHigh"), high * squaredRadius);
  glUniform1i(uniformLocation(program, "forcedLevel"), forcedLevel);
  glBindTextureUnit(0, entry.allDepth.id());
  glBindImageTexture(0, levels_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R8UI);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, histogram_.id());
  glDispatchCompute(GLuint(tilesX), GLuint(tilesY), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  checkGlError("choosing the ray resolution of each tile");
  return {levels_, tileSize};
}

TileHistogram RaymarchTilePass::histogram() const {
  TileHistogram counts{};
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(histogram_.id(), 0, sizeof counts, counts.data());
  return counts;
}

}  // namespace spindrift
