#include "passes/RaymarchPass.h"

#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

namespace spindrift {

RaymarchPass::RaymarchPass(const ShaderLibrary& shaders)
    : adaptiveProgram_(shaders.program({"raymarch_march.comp"}, {"ADAPTIVE_STEPS"})),
      uniformProgram_(shaders.program({"raymarch_march.comp"})),
      counters_(createBuffer()) {
  glNamedBufferStorage(counters_.id(), sizeof(RaymarchCounters), nullptr, GL_DYNAMIC_STORAGE_BIT);
}

RaymarchSamples RaymarchPass::run(const RaymarchInputs& in, float particleRadius,
                                  const LiquidParameters& parameters, int width, int height) {
  ensureTexture(depth_, GL_R32F, width, height);
  ensureTexture(normal_, GL_RGBA16F, width, height);
  ensureTexture(steps_, GL_R32F, width, height);
  const RaymarchCounters zeros;
  glNamedBufferSubData(counters_.id(), 0, sizeof zeros, &zeros);
  const GLuint program =
      (parameters.raymarch_stepping == "adaptive" ? adaptiveProgram_ : uniformProgram_).id();
  glUseProgram(program);
  bindRaymarchGrid(program, in.grid);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, counters_.id());
  const GLuint textures[] = {in.entry.allDepth.id(),      in.aggregateFront.eyeDepth.id(),
                             in.splashBack.eyeDepth.id(), in.aggregateBack.eyeDepth.id(),
                             in.background.eyeDepth.id(), in.entry.screenNormal.id(),
                             in.tiles.levels.id(),        in.mask.mask.id()};
  for (GLuint unit = 0; unit < 8; ++unit)
    glBindTextureUnit(unit, textures[unit]);
  glBindImageTexture(0, depth_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  glBindImageTexture(1, normal_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  glBindImageTexture(2, steps_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);

  const float smoothingRadius = in.grid.smoothingRadius;
  glUniform1f(uniformLocation(program, "iso"), parameters.raymarch_iso);
  glUniform1f(uniformLocation(program, "stepLength"), parameters.raymarch_step * particleRadius);
  glUniform1i(uniformLocation(program, "maxSteps"), parameters.raymarch_max_steps);
  glUniform1i(uniformLocation(program, "maxSkipSteps"), parameters.raymarch_max_skip_steps);
  // The iso-surface of several particles bulges out of their drawn shapes by up to h - r: rays start there.
  glUniform1f(uniformLocation(program, "entryBackoff"), std::max(smoothingRadius - particleRadius, 0.0f));
  glUniform1f(uniformLocation(program, "particleRadius"), particleRadius);
  glUniform1f(uniformLocation(program, "distanceWeight"),
              parameters.raymarch_normal_distance_weight / particleRadius);
  glUniform1f(uniformLocation(program, "sizeWeight"), parameters.raymarch_normal_size_weight);
  glUniform1i(uniformLocation(program, "tileSize"), in.tiles.tileSize);
  glUniform1i(uniformLocation(program, "hasSplash"), in.hasSplash ? 1 : 0);
  glUniform1i(uniformLocation(program, "hasAggregate"), in.hasAggregate ? 1 : 0);
  glUniform1i(uniformLocation(program, "clipToDomain"), in.domain ? 1 : 0);
  if (in.domain) {
    const glm::mat4 domainFromWorld = glm::inverse(in.domain->worldFromBox);
    glUniformMatrix4fv(uniformLocation(program, "domainFromWorld"), 1, GL_FALSE, &domainFromWorld[0][0]);
    glUniform3fv(uniformLocation(program, "domainLow"), 1, &in.domain->low[0]);
    glUniform3fv(uniformLocation(program, "domainHigh"), 1, &in.domain->high[0]);
  }
  glDispatchCompute(GLuint((width + 7) / 8), GLuint((height + 7) / 8), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
  checkGlError("ray marching the iso-surface");
  return {depth_, normal_, steps_};
}

RaymarchCounters RaymarchPass::counters() const {
  RaymarchCounters counts;
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(counters_.id(), 0, sizeof counts, &counts);
  return counts;
}

}  // namespace spindrift
