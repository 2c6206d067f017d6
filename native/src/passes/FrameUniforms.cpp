#include "passes/FrameUniforms.h"

#include <cmath>

#include <glm/trigonometric.hpp>

namespace spindrift {

FrameUniforms FrameUniforms::fromCamera(const Camera& camera) {
  FrameUniforms uniforms;
  uniforms.clipFromCamera = camera.clipFromCamera();
  uniforms.cameraFromWorld = camera.cameraFromWorld();
  uniforms.worldFromCamera = camera.worldFromCamera;
  const float width = float(camera.width), height = float(camera.height);
  uniforms.viewportSize = {width, height, 1.0f / width, 1.0f / height};
  uniforms.clipPlanes = {camera.nearClip, camera.farClip, std::log(camera.farClip / camera.nearClip), 0.0f};
  const float tanHalfY = std::tan(glm::radians(camera.fovYDegrees) * 0.5f);
  uniforms.tanHalfFov = {tanHalfY * camera.aspect(), tanHalfY, 0.0f, 0.0f};
  return uniforms;
}

void FrameUniformBuffer::update(const Camera& camera) {
  const FrameUniforms uniforms = FrameUniforms::fromCamera(camera);
  if (!buffer_) {
    buffer_ = createBuffer();
    glNamedBufferStorage(buffer_.id(), sizeof(FrameUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
  }
  glNamedBufferSubData(buffer_.id(), 0, sizeof(FrameUniforms), &uniforms);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffer_.id());
}

void drawFullscreenTriangle(GLuint emptyVertexArray) {
  glBindVertexArray(emptyVertexArray);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace spindrift
