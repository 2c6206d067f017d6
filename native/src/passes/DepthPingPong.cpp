#include "passes/DepthPingPong.h"

#include "passes/FrameUniforms.h"

namespace spindrift {

DepthPingPong::DepthPingPong() : framebuffer_(createFramebuffer()), emptyVertexArray_(createVertexArray()) {}

void DepthPingPong::prepare(int width, int height, const PixelTiles* tiles) {
  tiles_ = tiles;
  for (Texture2D& target : targets_)
    ensureTexture(target, GL_R32F, width, height);
  const float noSurface[4] = {1e10f, 0.0f, 0.0f, 0.0f};  // kNoSurfaceDepth
  if (tiles)  // one at a time: draw() attaches its target as the only one
    for (const Texture2D& target : targets_)
      clearColorTargets(framebuffer_.id(), {&target}, noSurface);
}

Texture2D& DepthPingPong::targetOtherThan(const Texture2D& source) {
  return source.id() == targets_[0].id() ? targets_[1] : targets_[0];
}

const Texture2D& DepthPingPong::draw(const Texture2D& source) {
  // The target is never the source, so a filter never reads the texture it writes.
  return drawInto(source, targetOtherThan(source));
}

const Texture2D& DepthPingPong::drawInto(const Texture2D& source, const Texture2D& target) {
  glNamedFramebufferTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, target.id(), 0);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  glViewport(0, 0, target.width, target.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glBindTextureUnit(0, source.id());
  drawFullscreen(emptyVertexArray_.id(), tiles_);
  checkGlError("filtering a depth layer");
  return target;
}

const Texture2D& DepthPingPong::drawRepeatedly(const Texture2D& source, int count) {
  const Texture2D* current = &source;
  for (int iteration = 0; iteration < count; ++iteration)
    current = &draw(*current);
  return *current;
}

const Texture2D& DepthPingPong::copy(const Texture2D& source) {
  Texture2D& target = targetOtherThan(source);
  glCopyImageSubData(source.id(), GL_TEXTURE_2D, 0, 0, 0, 0, target.id(), GL_TEXTURE_2D, 0, 0, 0, 0,
                     target.width, target.height, 1);
  checkGlError("copying a depth layer");
  return target;
}

}  // namespace spindrift
