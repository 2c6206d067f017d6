#include "spindrift/Particles.h"

#include <cmath>

namespace spindrift {

void Particles::reserve(std::size_t count) {
  positions.reserve(count);
  radii.reserve(count);
  kinds.reserve(count);
  life.reserve(count);
  velocities.reserve(count);
}

void Particles::append(const glm::vec3& position, float radius, ParticleKind kind, float lifeFrames,
                       const glm::vec3& velocity) {
  positions.push_back(position);
  radii.push_back(radius);
  kinds.push_back(kind);
  life.push_back(lifeFrames);
  velocities.push_back(velocity);
}

std::size_t appendValidParticles(Particles& into, const Particles& from) {
  auto finite = [](const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
  };
  std::size_t dropped = 0;
  into.reserve(into.size() + from.size());
  for (std::size_t i = 0; i < from.size(); ++i) {
    const float radius = from.radii[i];
    if (!finite(from.positions[i]) || !std::isfinite(radius) || !(radius > 0.0f)) {
      ++dropped;
      continue;
    }
    const float life = i < from.life.size() && std::isfinite(from.life[i]) ? from.life[i] : 0.0f;
    const glm::vec3 velocity =
        i < from.velocities.size() && finite(from.velocities[i]) ? from.velocities[i] : glm::vec3(0.0f);
    into.append(from.positions[i], radius, from.kinds[i], life, velocity);
  }
  return dropped;
}

const char* particleKindName(ParticleKind kind) {
  switch (kind) {
    case ParticleKind::Liquid:
      return "liquid";
    case ParticleKind::Spray:
      return "spray";
    case ParticleKind::Bubble:
      return "bubble";
    case ParticleKind::Foam:
      return "foam";
  }
  return "unknown";
}

ParticleCounts countByKind(const Particles& particles) {
  ParticleCounts counts;
  for (ParticleKind kind : particles.kinds) {
    switch (kind) {
      case ParticleKind::Liquid:
        ++counts.liquid;
        break;
      case ParticleKind::Spray:
        ++counts.spray;
        break;
      case ParticleKind::Bubble:
        ++counts.bubble;
        break;
      case ParticleKind::Foam:
        ++counts.foam;
        break;
    }
  }
  return counts;
}

}  // namespace spindrift
