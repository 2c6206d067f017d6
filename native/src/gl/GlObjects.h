#pragma once

#include <GL/glew.h>

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>

namespace spindrift {

enum class GlObjectType { Texture, Buffer, Framebuffer, VertexArray, Program, Query, Count };

/// How many GL objects of a type are alive in this process: the leak test watches these stay flat.
long liveGlObjectCount(GlObjectType type);

namespace gl_detail {
std::atomic<long>& liveCounter(GlObjectType type);
void deleteObject(GlObjectType type, GLuint id);
}  // namespace gl_detail

/// Owns one GL object name and deletes it when it goes; movable, not copyable. Must be destroyed on the
/// thread whose context made it (the Renderer's GL thread).
template <GlObjectType Type>
class GlObject {
 public:
  GlObject() = default;
  explicit GlObject(GLuint id) : id_(id) {
    if (id_) ++gl_detail::liveCounter(Type);
  }
  ~GlObject() { reset(); }
  GlObject(GlObject&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  GlObject& operator=(GlObject&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  GlObject(const GlObject&) = delete;
  GlObject& operator=(const GlObject&) = delete;

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (!id_) return;
    gl_detail::deleteObject(Type, id_);
    --gl_detail::liveCounter(Type);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

using TextureObject = GlObject<GlObjectType::Texture>;
using BufferObject = GlObject<GlObjectType::Buffer>;
using FramebufferObject = GlObject<GlObjectType::Framebuffer>;
using VertexArrayObject = GlObject<GlObjectType::VertexArray>;

/// A linked program, shared: ShaderLibrary gives every pass that asks for the same sources the same program,
/// so a process loads and llvmpipe compiles each once. A program's uniforms are its state, so every pass sets
/// its own before it draws. The GL object is deleted with the last copy.
class ProgramObject {
 public:
  ProgramObject() = default;
  explicit ProgramObject(GLuint id)
      : owner_(id ? std::make_shared<GlObject<GlObjectType::Program>>(id) : nullptr) {}

  GLuint id() const { return owner_ ? owner_->id() : 0; }
  explicit operator bool() const { return id() != 0; }
  void reset() { owner_.reset(); }

 private:
  std::shared_ptr<GlObject<GlObjectType::Program>> owner_;
};
using QueryObject = GlObject<GlObjectType::Query>;

/// A 2D texture with immutable storage, nearest filtering and clamped edges unless told otherwise.
struct Texture2D {
  TextureObject object;
  int width = 0;
  int height = 0;
  GLenum internalFormat = 0;
  int layers = 0;  ///< 0 for a GL_TEXTURE_2D; the layer count of a GL_TEXTURE_2D_ARRAY (ensureTextureArray)

  GLuint id() const { return object.id(); }
  explicit operator bool() const { return bool(object); }
  bool matches(int w, int h, GLenum format, int layerCount = 0) const {
    return object && width == w && height == h && internalFormat == format && layers == layerCount;
  }
};

/// Makes `texture` a w×h texture of `internalFormat` unless it already is one (render targets are reused
/// across frames and reallocated only when the frame size changes).
void ensureTexture(Texture2D& texture, GLenum internalFormat, int width, int height);
/// The same for a 2D array texture of `layers` layers.
void ensureTextureArray(Texture2D& texture, GLenum internalFormat, int width, int height, int layers);
/// Uploads top-row-first float pixels (1, 3 or 4 channels) into a new texture, flipped so texel row 0 is the
/// image's bottom row, as GL's window coordinates expect. `linear` selects bilinear filtering.
void uploadTexture(Texture2D& texture, GLenum internalFormat, int width, int height, int channels,
                   const float* pixels, bool linear);

BufferObject createBuffer();
/// A buffer of `count` uint32 counters that shaders add to atomically, which the host reads back
/// (readCounters).
BufferObject createCounters(std::size_t count);
/// The first `count` counters of a createCounters buffer, once the shaders' atomic writes have landed (waits
/// for the GPU).
void readCounters(const BufferObject& counters, std::uint32_t* values, std::size_t count);
FramebufferObject createFramebuffer();
VertexArrayObject createVertexArray();
QueryObject createQuery(GLenum target);

/// Throws Error naming `what` when the GL error flag is set.
void checkGlError(const char* what);

}  // namespace spindrift
