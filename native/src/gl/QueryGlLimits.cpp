#include "gl/QueryGlLimits.h"

#include <GL/glew.h>

namespace spindrift {

GlLimits queryGlLimits() {
  GlLimits limits;
  GLint viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limits.maxTextureSize);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &limits.maxFramebufferWidth);
  glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &limits.maxFramebufferHeight);
  limits.maxViewportWidth = viewport[0];
  limits.maxViewportHeight = viewport[1];
  return limits;
}

}  // namespace spindrift
