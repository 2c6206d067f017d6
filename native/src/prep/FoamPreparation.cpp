#include "prep/FoamPreparation.h"

#include <algorithm>

#include <glm/geometric.hpp>

#include "prep/ViewFrustum.h"

namespace spindrift {

float foamDrawnRadius(float radius, ParticleKind kind, std::size_t index, const FoamParameters& parameters) {
  // The particle's index is the only identity a cache gives it; the paper uses its id the same way.
  const float irregularity = float(index % std::size_t(parameters.radius_variation) + 1);
  const float kindScale = kind == ParticleKind::Bubble ? parameters.bubble_radius_scale : 1.0f;
  return radius * kindScale / irregularity;
}

float foamNormalisedAge(float lifeFrames, const FoamParameters& parameters) {
  if (!(lifeFrames > 0.0f) || !(parameters.lifetime_frames > 0.0f)) return 0.0f;
  return std::clamp(1.0f - lifeFrames / parameters.lifetime_frames, 0.0f, 1.0f);
}

FoamPreparation prepareFoam(const Particles& particles, const Camera& camera,
                            const FoamParameters& parameters) {
  const ViewFrustum frustum(camera);
  FoamPreparation result;
  std::size_t foamIndex = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const ParticleKind kind = particles.kinds[i];
    if (kind == ParticleKind::Liquid) continue;
    const float radius = foamDrawnRadius(particles.radii[i], kind, foamIndex++, parameters);
    const glm::vec3 cameraCentre = frustum.cameraFromWorld(particles.positions[i]);
    // A sprite cannot cover a sphere that contains the camera, so those are culled with the invisible ones.
    if (!frustum.reachedBySphere(cameraCentre, radius) ||
        glm::dot(cameraCentre, cameraCentre) <= radius * radius) {
      ++result.culled;
      continue;
    }
    const FoamType type = kind == ParticleKind::Spray    ? FoamType::Spray
                          : kind == ParticleKind::Bubble ? FoamType::Bubble
                                                         : FoamType::Surface;
    (type == FoamType::Spray ? result.spray : type == FoamType::Bubble ? result.bubble : result.surface)++;
    result.instances.push_back(
        {glm::vec4(particles.positions[i], radius),
         glm::vec4(float(int(type)), foamNormalisedAge(particles.life[i], parameters), 0.0f, 0.0f)});
  }
  return result;
}

}  // namespace spindrift
