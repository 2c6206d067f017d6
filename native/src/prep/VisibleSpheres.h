#pragma once

#include <cstddef>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "spindrift/Camera.h"
#include "spindrift/Particles.h"

namespace spindrift {

/// The camera's view frustum, for culling spheres on the CPU.
class ViewFrustum {
 public:
  explicit ViewFrustum(const Camera& camera);
  /// Whether a world-space sphere can reach the frustum between the clip planes. Spheres that contain the
  /// camera are left out too: a quad cannot cover them.
  bool reaches(const glm::vec3& worldCentre, float radius) const;

 private:
  glm::mat4 cameraFromWorld_;
  glm::vec3 sidePlanes_[4];  ///< Inward unit normals of the side planes, which pass through the camera.
  float nearClip_;
  float farClip_;
};

/// The spheres the impostor pass draws: world centre in xyz, radius in w.
struct VisibleSpheres {
  std::vector<glm::vec4> spheres;
  std::size_t culled = 0;  ///< Outside the view frustum, or containing the camera.
};

/// Keeps the particles of `kind` whose sphere can reach the view frustum between the clip planes. Spheres
/// that contain the camera are left out too: a quad cannot cover them (the liquid pipeline handles that
/// case).
VisibleSpheres visibleSpheres(const Particles& particles, ParticleKind kind, const Camera& camera);

}  // namespace spindrift
