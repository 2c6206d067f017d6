#pragma once

#include <initializer_list>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "framedata/PixelTiles.h"
#include "gl/GlObjects.h"
#include "spindrift/Camera.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// The frame block every shader includes (shaders/lib/frame.glsl), std140, bound at uniform binding 0.
struct FrameUniforms {
  glm::mat4 clipFromCamera;
  glm::mat4 cameraFromWorld;
  glm::mat4 worldFromCamera;
  glm::vec4 viewportSize;  ///< width, height, 1/width, 1/height
  glm::vec4 clipPlanes;    ///< near, far, 1 / far, 0
  glm::vec4 tanHalfFov;    ///< tan(fov_x / 2), tan(fov_y / 2), 0, 0
  glm::vec4 pixelTiles;    ///< kPixelTileSize (framedata/PixelTiles.h), 0, 0, 0

  static FrameUniforms fromCamera(const Camera& camera);
};

/// The uniform buffer that holds FrameUniforms for the frame being drawn (binding 0), or for another view
/// such as a light's (another binding).
class FrameUniformBuffer {
 public:
  void update(const Camera& camera, GLuint binding = 0);

 private:
  BufferObject buffer_;
};

/// Draws the fullscreen triangle of shaders/fullscreen.vert into the bound framebuffer.
void drawFullscreenTriangle(GLuint emptyVertexArray);

/// Draws a point the tile's size over each tile `tiles` marks (shaders/fullscreen.vert), or the fullscreen
/// triangle when `tiles` is null. A pass that draws tiles first clears its targets to what it writes where
/// there is no liquid, so both ways leave the same values in every pixel.
void drawFullscreen(GLuint emptyVertexArray, const PixelTiles* tiles);

/// Attaches `targets` as colour attachments 0, 1, ... (a null target leaves its draw buffer GL_NONE), makes
/// them the draw buffers, binds the framebuffer and sets the viewport to the first target's size.
void bindColorTargets(GLuint framebuffer, std::initializer_list<const Texture2D*> targets);

/// Clears `targets` to `value` through `framebuffer`, which is left bound with them attached: a clear that
/// llvmpipe's rasterizer threads do in their bins, where glClearTexImage fills the texture on the caller's.
void clearColorTargets(GLuint framebuffer, std::initializer_list<const Texture2D*> targets,
                       const float value[4]);

/// Sets shaders/lib/domain_box.glsl's uniforms of `program` (in use) to `domain`, or to none when it is null.
void setDomainBoxUniforms(GLuint program, const DomainBox* domain);

}  // namespace spindrift
