#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec4.hpp>

#include "spindrift/Camera.h"
#include "spindrift/Particles.h"

namespace spindrift {

/// The spheres the impostor pass draws: world centre in xyz, radius in w.
struct VisibleSpheres {
  std::vector<glm::vec4> spheres;
  std::size_t culled = 0;  ///< Outside the view frustum, or containing the camera.
};

/// Keeps the particles of `kind` whose sphere can reach the view frustum between the clip planes. Spheres
/// that contain the camera are left out too: a quad cannot cover them (the liquid pipeline handles that case).
VisibleSpheres visibleSpheres(const Particles& particles, ParticleKind kind, const Camera& camera);

}  // namespace spindrift
