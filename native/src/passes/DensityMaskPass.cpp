#include "passes/DensityMaskPass.h"

namespace spindrift {

DensityMaskPass::DensityMaskPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"raymarch_density_mask.comp"})) {}

DensityMaskData DensityMaskPass::run(const RaymarchGridData& grid, const LiquidParameters& parameters) {
  const std::size_t cells = grid.grid.cellCount();
  if (cells > cellCapacity_) {
    cellCapacity_ = cells;
    for (BufferObject* buffer : {&convolvedX_, &convolvedXY_}) {
      *buffer = createBuffer();
      glNamedBufferStorage(buffer->id(), GLsizeiptr(cells * sizeof(float)), nullptr, 0);
    }
  }
  const glm::ivec3 texels = grid.grid.size / 2;
  if (texels != texels_) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_3D, 1, &id);
    mask_ = TextureObject(id);
    glTextureStorage3D(id, 1, GL_R8UI, texels.x, texels.y, texels.z);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    texels_ = texels;
  }
  const GLuint program = program_.id();
  glUseProgram(program);
  bindRaymarchGrid(program, grid);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, convolvedX_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, convolvedXY_.id());
  glBindImageTexture(0, mask_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R8UI);
  glUniform1f(uniformLocation(program, "centreWeight"), parameters.raymarch_kernel_centre);
  glUniform1f(uniformLocation(program, "sideWeight"), parameters.raymarch_kernel_side);
  glUniform1f(uniformLocation(program, "iso"), parameters.raymarch_iso);
  const GLint stage = uniformLocation(program, "stage");
  const std::size_t blocks = std::size_t(texels.x) * texels.y * texels.z;
  const std::size_t invocations[3] = {cells, cells, blocks};
  for (int i = 0; i < 3; ++i) {
    glUniform1i(stage, i);
    glDispatchCompute(GLuint((invocations[i] + 63) / 64), 1, 1);
    glMemoryBarrier(i < 2 ? GL_SHADER_STORAGE_BARRIER_BIT : GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  checkGlError("making the binary density grid");
  return {mask_, texels_};
}

std::vector<std::uint8_t> DensityMaskPass::readCells() const {
  const glm::ivec3 cells = texels_ * 2;
  std::vector<std::uint8_t> packed(std::size_t(texels_.x) * texels_.y * texels_.z);
  glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(mask_.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, GLsizei(packed.size()), packed.data());
  checkGlError("reading the binary density grid");
  std::vector<std::uint8_t> unpacked(std::size_t(cells.x) * cells.y * cells.z);
  for (int z = 0; z < cells.z; ++z)
    for (int y = 0; y < cells.y; ++y)
      for (int x = 0; x < cells.x; ++x) {
        const std::uint8_t bits = packed[(std::size_t(z / 2) * texels_.y + y / 2) * texels_.x + x / 2];
        unpacked[(std::size_t(z) * cells.y + y) * cells.x + x] =
            (bits >> ((x & 1) | (y & 1) << 1 | (z & 1) << 2)) & 1;
      }
  return unpacked;
}

}  // namespace spindrift
