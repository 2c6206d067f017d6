#include "prep/VisibleSpheres.h"

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

namespace spindrift {

VisibleSpheres visibleSpheres(const Particles& particles, ParticleKind kind, const Camera& camera) {
  const glm::mat4 cameraFromWorld = camera.cameraFromWorld();
  const float tanHalfY = std::tan(glm::radians(camera.fovYDegrees) * 0.5f);
  const float tanHalfX = tanHalfY * camera.aspect();
  // Inward unit normals of the four side planes, which pass through the camera (camera space, -Z forward).
  const glm::vec3 sidePlanes[4] = {
      glm::normalize(glm::vec3(1.0f, 0.0f, -tanHalfX)), glm::normalize(glm::vec3(-1.0f, 0.0f, -tanHalfX)),
      glm::normalize(glm::vec3(0.0f, 1.0f, -tanHalfY)), glm::normalize(glm::vec3(0.0f, -1.0f, -tanHalfY))};

  VisibleSpheres result;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.kinds[i] != kind) continue;
    const float radius = particles.radii[i];
    const glm::vec3 centre = glm::vec3(cameraFromWorld * glm::vec4(particles.positions[i], 1.0f));
    const float eyeDepth = -centre.z;
    bool visible = eyeDepth + radius >= camera.nearClip && eyeDepth - radius <= camera.farClip &&
                   glm::dot(centre, centre) > radius * radius;
    for (const glm::vec3& plane : sidePlanes) visible = visible && glm::dot(plane, centre) >= -radius;
    if (visible) result.spheres.emplace_back(particles.positions[i], radius);
    else ++result.culled;
  }
  return result;
}

}  // namespace spindrift
