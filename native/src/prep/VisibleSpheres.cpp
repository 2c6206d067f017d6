#include "prep/VisibleSpheres.h"

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

bool ViewFrustum::reaches(const glm::vec3& worldCentre, float radius) const {
  const glm::vec3 centre = glm::vec3(cameraFromWorld_ * glm::vec4(worldCentre, 1.0f));
  const float eyeDepth = -centre.z;
  bool visible = eyeDepth + radius >= nearClip_ && eyeDepth - radius <= farClip_ &&
                 glm::dot(centre, centre) > radius * radius;
  for (const glm::vec3& plane : sidePlanes_)
    visible = visible && glm::dot(plane, centre) >= -radius;
  return visible;
}

VisibleSpheres visibleSpheres(const Particles& particles, ParticleKind kind, const Camera& camera) {
  const ViewFrustum frustum(camera);
  VisibleSpheres result;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.kinds[i] != kind) continue;
    if (frustum.reaches(particles.positions[i], particles.radii[i]))
      result.spheres.emplace_back(particles.positions[i], particles.radii[i]);
    else
      ++result.culled;
  }
  return result;
}

}  // namespace spindrift
