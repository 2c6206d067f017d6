#include "passes/RaymarchUpsamplePass.h"

namespace spindrift {

RaymarchUpsamplePass::RaymarchUpsamplePass(const ShaderLibrary& shaders)
    : program_(shaders.program({"raymarch_upsample.comp"})) {}

MarchedFronts RaymarchUpsamplePass::run(const RaymarchSamples& samples, const RaymarchTileData& tiles,
                                        const DepthLayer& splashFront, const DepthLayer& aggregateFront,
                                        int width, int height) {
  ensureTexture(splashDepth_, GL_R32F, width, height);
  ensureTexture(splashNormal_, GL_RGBA16F, width, height);
  ensureTexture(aggregateDepth_, GL_R32F, width, height);
  ensureTexture(aggregateNormal_, GL_RGBA16F, width, height);
  const GLuint program = program_.id();
  glUseProgram(program);
  const GLuint textures[] = {samples.depth.id(),        samples.normal.id(),     tiles.levels.id(),
                             splashFront.eyeDepth.id(), splashFront.normal.id(), aggregateFront.eyeDepth.id(),
                             aggregateFront.normal.id()};
  for (GLuint unit = 0; unit < 7; ++unit)
    glBindTextureUnit(unit, textures[unit]);
  glBindImageTexture(0, splashDepth_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  glBindImageTexture(1, splashNormal_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  glBindImageTexture(2, aggregateDepth_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  glBindImageTexture(3, aggregateNormal_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  glUniform1i(uniformLocation(program, "tileSize"), tiles.tileSize);
  glDispatchCompute(GLuint((width + 7) / 8), GLuint((height + 7) / 8), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  checkGlError("interpolating the marched surface to full resolution");
  return {{splashDepth_, splashNormal_}, {aggregateDepth_, aggregateNormal_}};
}

}  // namespace spindrift
