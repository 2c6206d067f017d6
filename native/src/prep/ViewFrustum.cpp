#include "prep/ViewFrustum.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace spindrift {

ViewFrustum::ViewFrustum(const Camera& camera)
    : cameraFromWorld_(camera.cameraFromWorld()), nearClip_(camera.nearClip), farClip_(camera.farClip) {
  const float tanHalfY = std::tan(glm::radians(camera.fovYDegrees) * 0.5f);
  const float tanHalfX = tanHalfY * camera.aspect();
  // Camera space looks down -Z.
  sidePlanes_[0] = glm::normalize(glm::vec3(1.0f, 0.0f, -tanHalfX));
  sidePlanes_[1] = glm::normalize(glm::vec3(-1.0f, 0.0f, -tanHalfX));
  sidePlanes_[2] = glm::normalize(glm::vec3(0.0f, 1.0f, -tanHalfY));
  sidePlanes_[3] = glm::normalize(glm::vec3(0.0f, -1.0f, -tanHalfY));
}

bool ViewFrustum::reachedBySphere(const glm::vec3& cameraCentre, float radius) const {
  const float eyeDepth = -cameraCentre.z;
  bool reached = eyeDepth + radius >= nearClip_ && eyeDepth - radius <= farClip_;
  for (const glm::vec3& plane : sidePlanes_)
    reached = reached && glm::dot(plane, cameraCentre) >= -radius;
  return reached;
}

}  // namespace spindrift
