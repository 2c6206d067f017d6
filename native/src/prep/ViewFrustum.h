#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "spindrift/Camera.h"

namespace spindrift {

/// The camera's view volume between its clip planes, for culling spheres on the CPU.
class ViewFrustum {
 public:
  explicit ViewFrustum(const Camera& camera);

  glm::vec3 cameraFromWorld(const glm::vec3& world) const {
    return glm::vec3(cameraFromWorld_ * glm::vec4(world, 1.0f));
  }
  /// Whether a sphere, its centre in camera space, can reach the frustum between the clip planes. The test
  /// is conservative near the frustum's edges (a sphere beyond an edge but within `radius` of both planes
  /// that meet there is kept), which only costs a few extra instances.
  bool reachedBySphere(const glm::vec3& cameraCentre, float radius) const;

 private:
  glm::mat4 cameraFromWorld_;
  float nearClip_;
  float farClip_;
  glm::vec3 sidePlanes_[4];  // Inward unit normals of the side planes, which pass through the camera.
};

}  // namespace spindrift
