#include "spindrift/Particles.h"

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

const char* particleKindName(ParticleKind kind) {
  switch (kind) {
    case ParticleKind::Liquid: return "liquid";
    case ParticleKind::Spray: return "spray";
    case ParticleKind::Bubble: return "bubble";
    case ParticleKind::Foam: return "foam";
  }
  return "unknown";
}

ParticleCounts countByKind(const Particles& particles) {
  ParticleCounts counts;
  for (ParticleKind kind : particles.kinds) {
    switch (kind) {
      case ParticleKind::Liquid: ++counts.liquid; break;
      case ParticleKind::Spray: ++counts.spray; break;
      case ParticleKind::Bubble: ++counts.bubble; break;
      case ParticleKind::Foam: ++counts.foam; break;
    }
  }
  return counts;
}

}  // namespace spindrift
