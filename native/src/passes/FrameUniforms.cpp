#include "passes/FrameUniforms.h"

#include <cmath>

#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include "gl/ShaderLibrary.h"

namespace spindrift {

FrameUniforms FrameUniforms::fromCamera(const Camera& camera) {
  FrameUniforms uniforms;
  uniforms.clipFromCamera = camera.clipFromCamera();
  uniforms.cameraFromWorld = camera.cameraFromWorld();
  uniforms.worldFromCamera = camera.worldFromCamera;
  const float width = float(camera.width), height = float(camera.height);
  uniforms.viewportSize = {width, height, 1.0f / width, 1.0f / height};
  uniforms.clipPlanes = {camera.nearClip, camera.farClip, 1.0f / camera.farClip, 0.0f};
  const float tanHalfY = std::tan(glm::radians(camera.fovYDegrees) * 0.5f);
  uniforms.tanHalfFov = {tanHalfY * camera.aspect(), tanHalfY, 0.0f, 0.0f};
  uniforms.pixelTiles = {float(kPixelTileSize), 0.0f, 0.0f, 0.0f};
  return uniforms;
}

void FrameUniformBuffer::update(const Camera& camera, GLuint binding) {
  const FrameUniforms uniforms = FrameUniforms::fromCamera(camera);
  if (!buffer_) {
    buffer_ = createBuffer();
    glNamedBufferStorage(buffer_.id(), sizeof(FrameUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
  }
  glNamedBufferSubData(buffer_.id(), 0, sizeof(FrameUniforms), &uniforms);
  glBindBufferBase(GL_UNIFORM_BUFFER, binding, buffer_.id());
}

void drawFullscreenTriangle(GLuint emptyVertexArray) {
  glBindVertexArray(emptyVertexArray);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void drawFullscreen(GLuint emptyVertexArray, const PixelTiles* tiles) {
  if (!tiles) {
    drawFullscreenTriangle(emptyVertexArray);
    return;
  }
  // Vertex 3 + i is tile i as a point (fullscreen.vert).
  const Texture2D& marked = tiles->marked;
  glBindTextureUnit(kPixelTilesTextureUnit, marked.id());
  glBindVertexArray(emptyVertexArray);
  glEnable(GL_PROGRAM_POINT_SIZE);
  // A point whose centre leaves the viewport is clipped whole, and the last column or row of tiles of a frame
  // whose side is more than half a tile short of a whole tile (38, 100, 900 pixels) has its centre beyond it:
  // those tiles went unshaded. The viewport is widened to whole tiles for the draw (fullscreen.vert places
  // the points in it); rendering stops at the targets' own edge.
  GLint viewport[4];
  glGetIntegerv(GL_VIEWPORT, viewport);
  glViewport(viewport[0], viewport[1], marked.width * kPixelTileSize, marked.height * kPixelTileSize);
  glDrawArrays(GL_POINTS, 3, marked.width * marked.height);
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  glDisable(GL_PROGRAM_POINT_SIZE);
}

void bindColorTargets(GLuint framebuffer, std::initializer_list<const Texture2D*> targets) {
  GLenum drawBuffers[8];
  GLsizei count = 0;
  int width = 0, height = 0;
  for (const Texture2D* target : targets) {
    const GLenum attachment = GL_COLOR_ATTACHMENT0 + GLenum(count);
    glNamedFramebufferTexture(framebuffer, attachment, target ? target->id() : 0, 0);
    drawBuffers[count++] = target ? attachment : GL_NONE;
    if (target && width == 0) {
      width = target->width;
      height = target->height;
    }
  }
  // Attachments left from an earlier use (perhaps of another size, or since deleted) would clip rendering to
  // the smallest attachment: detach every one not named.
  for (GLint unused = count; unused < 8; ++unused)
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0 + GLenum(unused), 0, 0);
  glNamedFramebufferDrawBuffers(framebuffer, count, drawBuffers);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
}

void clearColorTargets(GLuint framebuffer, std::initializer_list<const Texture2D*> targets,
                       const float value[4]) {
  bindColorTargets(framebuffer, targets);
  for (GLint drawBuffer = 0; drawBuffer < GLint(targets.size()); ++drawBuffer)
    glClearNamedFramebufferfv(framebuffer, GL_COLOR, drawBuffer, value);
}

void setDomainBoxUniforms(GLuint program, const DomainBox* domain) {
  glUniform1i(uniformLocation(program, "hasDomain"), domain ? 1 : 0);
  if (!domain) return;
  const glm::mat4 domainFromWorld = glm::inverse(domain->worldFromBox);
  glUniformMatrix4fv(uniformLocation(program, "domainFromWorld"), 1, GL_FALSE, &domainFromWorld[0][0]);
  glUniform3fv(uniformLocation(program, "domainLow"), 1, &domain->low.x);
  glUniform3fv(uniformLocation(program, "domainHigh"), 1, &domain->high.x);
}

}  // namespace spindrift
