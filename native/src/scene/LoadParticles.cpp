#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "io/ParticleFile.h"
#include "spindrift/Error.h"
#include "spindrift/Scene.h"

namespace spindrift {
namespace {

ParticleKind foamKindFromFlag(std::int32_t flag) {
  switch (flag) {
    case 2:
      return ParticleKind::Spray;
    case 4:
      return ParticleKind::Bubble;
    default:
      return ParticleKind::Foam;  // Mantaflow's 8, and anything a PLY writer calls foam otherwise.
  }
}

bool isFinite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void appendSource(const ParticleSource& source, const ParticleFileData& data, Particles& particles,
                  std::size_t& dropped) {
  const glm::mat3 linearPart(source.worldFromFile);
  const std::size_t count = data.positions.size();
  for (std::size_t i = 0; i < count; ++i) {
    const float radius = data.radii.empty() ? source.radius : data.radii[i];
    if (!isFinite(data.positions[i]) || !std::isfinite(radius) || !(radius > 0.0f)) {
      ++dropped;
      continue;
    }
    ParticleKind kind = ParticleKind::Liquid;
    if (source.role == ParticleRole::Foam)
      kind = source.kind              ? *source.kind
             : data.typeFlags.empty() ? ParticleKind::Foam
                                      : foamKindFromFlag(data.typeFlags[i]);
    const glm::vec3 world = glm::vec3(source.worldFromFile * glm::vec4(data.positions[i], 1.0f));
    if (!isFinite(world)) {  // A huge but finite position can still overflow in the transform.
      ++dropped;
      continue;
    }
    const glm::vec3 velocity = data.velocities.empty() ? glm::vec3(0.0f) : linearPart * data.velocities[i];
    particles.append(world, radius, kind, data.life.empty() ? 0.0f : data.life[i],
                     isFinite(velocity) ? velocity : glm::vec3(0.0f));
  }
}

}  // namespace

std::filesystem::path pathForFrame(const std::filesystem::path& pattern, int frame) {
  std::string name = pattern.filename().string();
  const std::size_t last = name.rfind('#');
  if (last == std::string::npos) return pattern;
  std::size_t first = last;
  while (first > 0 && name[first - 1] == '#')
    --first;
  const int width = int(last - first + 1);
  char digits[32];
  std::snprintf(digits, sizeof digits, frame < 0 ? "-%0*d" : "%0*d", width, std::abs(frame));
  name.replace(first, last - first + 1, digits);
  return pattern.parent_path() / name;
}

Particles loadParticles(const Scene& scene, int frame, ParticleCounts* countsOut) {
  Particles particles;
  std::size_t dropped = 0;
  for (const ParticleSource& source : scene.particles) {
    const std::filesystem::path path = pathForFrame(source.path, frame);
    if (!std::filesystem::exists(path))
      throw Error(path.string() + ": no such particle file (frame " + std::to_string(frame) + " of " +
                  source.path.string() + ")");
    const ParticleFileData data = readParticleFile(path, source.grid);
    particles.reserve(particles.size() + data.positions.size());
    appendSource(source, data, particles, dropped);
  }
  if (countsOut) {
    *countsOut = countByKind(particles);
    countsOut->droppedInvalid = dropped;
  }
  return particles;
}

}  // namespace spindrift
