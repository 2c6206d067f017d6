#include "passes/RaymarchGridPass.h"

#include <algorithm>

namespace spindrift {
namespace {

constexpr GLuint kGroupSize = 64;
constexpr std::size_t kBlockCells = 1024;  // cells summed per invocation of the scan (raymarch_grid.comp)

GLuint groupsFor(std::size_t invocations) {
  return GLuint((invocations + kGroupSize - 1) / kGroupSize);
}

BufferObject storageBuffer(std::size_t bytes) {
  BufferObject buffer = createBuffer();
  glNamedBufferStorage(buffer.id(), GLsizeiptr(std::max<std::size_t>(bytes, 16)), nullptr,
                       GL_DYNAMIC_STORAGE_BIT);
  return buffer;
}

}  // namespace

void bindRaymarchGrid(GLuint program, const RaymarchGridData& data) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, data.cellCounts.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, data.cellStarts.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, data.sortedParticles.id());
  // Not every program reads every grid uniform; glUniform ignores the location -1 of an inactive one.
  glUniform3fv(glGetUniformLocation(program, "gridOrigin"), 1, &data.grid.origin.x);
  glUniform1f(glGetUniformLocation(program, "cellSize"), data.grid.cellSize);
  glUniform3iv(glGetUniformLocation(program, "gridSize"), 1, &data.grid.size.x);
  glUniform1f(glGetUniformLocation(program, "smoothingRadius"), data.smoothingRadius);
}

RaymarchGridPass::RaymarchGridPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"raymarch_grid.comp"})) {
  ensureCapacity(1, 8);
}

// Grow-only buffers: a sequence reallocates only when a frame needs more than any before it.
void RaymarchGridPass::ensureCapacity(std::size_t particles, std::size_t cells) {
  if (particles > particleCapacity_) {
    particleCapacity_ = particles;
    particles_ = storageBuffer(particles * sizeof(float) * 4);
    sortedParticles_ = storageBuffer(particles * sizeof(float) * 4);
    slots_ = storageBuffer(particles * sizeof(std::uint32_t) * 2);
  }
  if (cells > cellCapacity_) {
    cellCapacity_ = cells;
    cellCounts_ = storageBuffer(cells * sizeof(std::uint32_t));
    cellStarts_ = storageBuffer(cells * sizeof(std::uint32_t));
    blockSums_ = storageBuffer((cells + kBlockCells - 1) / kBlockCells * sizeof(std::uint32_t));
  }
}

RaymarchGridData RaymarchGridPass::run(const RaymarchPreparation& preparation) {
  const std::size_t particleCount = preparation.particles.size();
  const std::size_t cells = preparation.grid.cellCount();
  ensureCapacity(particleCount, cells);
  if (particleCount > 0)
    glNamedBufferSubData(particles_.id(), 0, GLsizeiptr(particleCount * sizeof(glm::vec4)),
                         preparation.particles.data());
  const std::uint32_t zero = 0;
  glClearNamedBufferSubData(cellCounts_.id(), GL_R32UI, 0, GLsizeiptr(cells * sizeof(std::uint32_t)),
                            GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  RaymarchGridData data{cellCounts_, cellStarts_, sortedParticles_, preparation.grid,
                        preparation.smoothingRadius};
  const GLuint program = program_.id();
  glUseProgram(program);
  bindRaymarchGrid(program, data);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, particles_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, slots_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, blockSums_.id());
  const std::size_t blocks = (cells + kBlockCells - 1) / kBlockCells;
  glUniform1ui(uniformLocation(program, "particleCount"), GLuint(particleCount));
  glUniform1ui(uniformLocation(program, "totalCells"), GLuint(cells));
  glUniform1ui(uniformLocation(program, "blockCount"), GLuint(blocks));
  const GLint stage = uniformLocation(program, "stage");
  const std::size_t invocations[5] = {particleCount, blocks, 1, blocks, particleCount};
  for (int i = 0; i < 5; ++i) {
    if (invocations[i] == 0) continue;
    glUniform1i(stage, i);
    glDispatchCompute(groupsFor(invocations[i]), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  checkGlError("building the ray-marching neighbour grid");
  return data;
}

}  // namespace spindrift
