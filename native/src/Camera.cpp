#include "spindrift/Camera.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace spindrift {

Camera Camera::lookAt(int width, int height, float fovYDegrees, const glm::vec3& position,
                      const glm::vec3& target, const glm::vec3& up) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  camera.fovYDegrees = fovYDegrees;
  // glm::lookAt builds camera-from-world with the camera looking down -Z and +Y up: Blender's convention.
  camera.worldFromCamera = glm::inverse(glm::lookAt(position, target, up));
  return camera;
}

glm::mat4 Camera::cameraFromWorld() const {
  return glm::affineInverse(worldFromCamera);
}

glm::mat4 Camera::clipFromCamera() const {
  return glm::perspective(glm::radians(fovYDegrees), aspect(), nearClip, farClip);
}

glm::vec3 Camera::pixelAndDepthFromWorld(const glm::vec3& world) const {
  return pixelAndDepthFromCamera(glm::vec3(cameraFromWorld() * glm::vec4(world, 1.0f)));
}

glm::vec3 Camera::pixelAndDepthFromCamera(const glm::vec3& eye) const {
  const float eyeDepth = -eye.z;
  const float tanHalfY = std::tan(glm::radians(fovYDegrees) * 0.5f);
  const float ndcX = eye.x / (eyeDepth * tanHalfY * aspect());
  const float ndcY = eye.y / (eyeDepth * tanHalfY);
  return {(ndcX * 0.5f + 0.5f) * float(width), (0.5f - ndcY * 0.5f) * float(height), eyeDepth};
}

float Camera::pixelSizeAt(float eyeDepth) const {
  return 2.0f * eyeDepth * std::tan(glm::radians(fovYDegrees) * 0.5f) / float(height);
}

glm::vec3 Camera::worldFromPixelAndDepth(const glm::vec2& pixel, float eyeDepth) const {
  const float tanHalfY = std::tan(glm::radians(fovYDegrees) * 0.5f);
  const float ndcX = pixel.x / float(width) * 2.0f - 1.0f;
  const float ndcY = 1.0f - pixel.y / float(height) * 2.0f;
  const glm::vec3 eye{ndcX * tanHalfY * aspect() * eyeDepth, ndcY * tanHalfY * eyeDepth, -eyeDepth};
  return glm::vec3(worldFromCamera * glm::vec4(eye, 1.0f));
}

}  // namespace spindrift
