#include "prep/VisibleSpheres.h"

#include <glm/geometric.hpp>

#include "prep/ViewFrustum.h"

namespace spindrift {

VisibleSpheres visibleSpheres(const Particles& particles, ParticleKind kind, const Camera& camera) {
  const ViewFrustum frustum(camera);
  VisibleSpheres result;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.kinds[i] != kind) continue;
    const float radius = particles.radii[i];
    const glm::vec3 centre = frustum.cameraFromWorld(particles.positions[i]);
    const bool visible =
        frustum.reachedBySphere(centre, radius) && glm::dot(centre, centre) > radius * radius;
    if (visible)
      result.spheres.emplace_back(particles.positions[i], radius);
    else
      ++result.culled;
  }
  return result;
}

}  // namespace spindrift
