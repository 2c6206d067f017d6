#include "gl/GlObjects.h"

#include <algorithm>
#include <string>
#include <vector>

#include "spindrift/Error.h"

namespace spindrift {

namespace gl_detail {

std::atomic<long>& liveCounter(GlObjectType type) {
  static std::array<std::atomic<long>, std::size_t(GlObjectType::Count)> counters{};
  return counters[std::size_t(type)];
}

void deleteObject(GlObjectType type, GLuint id) {
  switch (type) {
    case GlObjectType::Texture:
      glDeleteTextures(1, &id);
      break;
    case GlObjectType::Buffer:
      glDeleteBuffers(1, &id);
      break;
    case GlObjectType::Framebuffer:
      glDeleteFramebuffers(1, &id);
      break;
    case GlObjectType::VertexArray:
      glDeleteVertexArrays(1, &id);
      break;
    case GlObjectType::Program:
      glDeleteProgram(id);
      break;
    case GlObjectType::Query:
      glDeleteQueries(1, &id);
      break;
    case GlObjectType::Count:
      break;
  }
}

}  // namespace gl_detail

long liveGlObjectCount(GlObjectType type) {
  return gl_detail::liveCounter(type).load();
}

namespace {

void allocateTexture(Texture2D& texture, GLenum internalFormat, int width, int height, int layers) {
  GLuint id = 0;
  glCreateTextures(layers > 0 ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D, 1, &id);
  texture.object = TextureObject(id);
  texture.width = width;
  texture.height = height;
  texture.internalFormat = internalFormat;
  texture.layers = layers;
  if (layers > 0)
    glTextureStorage3D(id, 1, internalFormat, width, height, layers);
  else
    glTextureStorage2D(id, 1, internalFormat, width, height);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  checkGlError("allocating a texture");
}

}  // namespace

void ensureTexture(Texture2D& texture, GLenum internalFormat, int width, int height) {
  if (!texture.matches(width, height, internalFormat))
    allocateTexture(texture, internalFormat, width, height, 0);
}

void ensureTextureArray(Texture2D& texture, GLenum internalFormat, int width, int height, int layers) {
  if (!texture.matches(width, height, internalFormat, layers))
    allocateTexture(texture, internalFormat, width, height, layers);
}

void uploadTexture(Texture2D& texture, GLenum internalFormat, int width, int height, int channels,
                   const float* pixels, bool linear) {
  ensureTexture(texture, internalFormat, width, height);
  const GLenum format = channels == 1 ? GL_RED : channels == 3 ? GL_RGB : GL_RGBA;
  const std::size_t rowFloats = std::size_t(width) * std::size_t(channels);
  std::vector<float> flipped(rowFloats * std::size_t(height));
  for (int row = 0; row < height; ++row)
    std::copy_n(pixels + std::size_t(height - 1 - row) * rowFloats, rowFloats,
                flipped.data() + std::size_t(row) * rowFloats);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTextureSubImage2D(texture.id(), 0, 0, 0, width, height, format, GL_FLOAT, flipped.data());
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, filter);
  glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, filter);
  checkGlError("uploading a texture");
}

BufferObject createBuffer() {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  return BufferObject(id);
}

BufferObject createCounters(std::size_t count) {
  BufferObject counters = createBuffer();
  glNamedBufferStorage(counters.id(), GLsizeiptr(count * sizeof(std::uint32_t)), nullptr,
                       GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
  return counters;
}

void readCounters(const BufferObject& counters, std::uint32_t* values, std::size_t count) {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // The shaders' atomic writes must land before the read.
  glGetNamedBufferSubData(counters.id(), 0, GLsizeiptr(count * sizeof(std::uint32_t)), values);
}

FramebufferObject createFramebuffer() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  return FramebufferObject(id);
}

VertexArrayObject createVertexArray() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  return VertexArrayObject(id);
}

QueryObject createQuery(GLenum target) {
  GLuint id = 0;
  glCreateQueries(target, 1, &id);
  return QueryObject(id);
}

void checkGlError(const char* what) {
  const GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  while (glGetError() != GL_NO_ERROR) {
  }
  const char* name = error == GL_OUT_OF_MEMORY                   ? "GL_OUT_OF_MEMORY"
                     : error == GL_INVALID_OPERATION             ? "GL_INVALID_OPERATION"
                     : error == GL_INVALID_VALUE                 ? "GL_INVALID_VALUE"
                     : error == GL_INVALID_ENUM                  ? "GL_INVALID_ENUM"
                     : error == GL_INVALID_FRAMEBUFFER_OPERATION ? "GL_INVALID_FRAMEBUFFER_OPERATION"
                                                                 : "GL error";
  throw Error(std::string("OpenGL failed while ") + what + ": " + name);
}

}  // namespace spindrift
