#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace spindrift {

/// What a particle is. The values are Mantaflow's secondary-particle flags (the `U` attribute), so a flag
/// read from a cache converts directly.
enum class ParticleKind : std::uint8_t { Liquid = 0, Spray = 2, Bubble = 4, Foam = 8 };

/// The particles of one frame, in world space. Every array has one entry per particle.
struct Particles {
  std::vector<glm::vec3> positions;
  std::vector<float> radii;  ///< World units.
  std::vector<ParticleKind> kinds;
  std::vector<float> life;            ///< Remaining life in frames; 0 where the source has none.
  std::vector<glm::vec3> velocities;  ///< World units per second; zero where the source has none.

  std::size_t size() const { return positions.size(); }
  void reserve(std::size_t count);
  void append(const glm::vec3& position, float radius, ParticleKind kind, float lifeFrames,
              const glm::vec3& velocity);
};

/// Particle counts of one frame, by kind, and what was left out before drawing.
struct ParticleCounts {
  std::size_t liquid = 0;
  std::size_t spray = 0;
  std::size_t bubble = 0;
  std::size_t foam = 0;
  std::size_t droppedInvalid = 0;  ///< NaN or Inf positions, and radii that are not finite and positive.

  std::size_t total() const { return liquid + spray + bubble + foam; }
};

/// Appends the particles of `from` whose position is finite and whose radius is finite and positive, as file
/// loading does; returns how many were dropped. `from.life` and `from.velocities` may be empty (0 then), and
/// non-finite values in them become 0.
std::size_t appendValidParticles(Particles& into, const Particles& from);

const char* particleKindName(ParticleKind kind);
ParticleCounts countByKind(const Particles& particles);

}  // namespace spindrift
