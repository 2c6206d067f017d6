#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "prep/LiquidPreparation.h"
#include "prep/MantaflowSurface.h"
#include "prep/NeighbourGrid.h"
#include "spindrift/Parameters.h"

namespace spindrift {

class ShapeMemory;

/// Yu and Turk's (2013) anisotropy constants, every length in particle radii so that they hold at any scale.
struct AnisotropySettings {
  float neighbourRadius = 2.5f;  ///< The neighbourhood radius R, in particle radii.
  float maxRatio = 4.0f;         ///< k_r.
  float minNeighbours = 25.0f;   ///< N_epsilon as applied to the frame (appliedMinNeighbours).
  float isotropicScale = 0.5f;   ///< k_n, in particle radii.
  float smoothing = 0.0f;        ///< lambda.
  float maxEllipsoidScale = 1.2f;
  float surfaceOffset = 0.0f;  ///< Every drawn semi-axis is grown by this, in particle radii.
  /// liquid.reach_radius: without meshSurface, an anisotropic particle is grown until its shortest semi-axis
  /// is at least r (by at least surfaceOffset).
  bool reachRadius = true;
  /// Mantaflow's surface over these particles (liquid.mesh_kernel_radius > 0): an anisotropic particle's
  /// offset is then its own, what makes its ellipsoid reach that surface, at most 1.5 surfaceOffset. Its
  /// searches are remembered for the frame's other views.
  MantaflowSurfaceSearch* meshSurface = nullptr;
  /// The camera's position: particles whose neighbourhood faces away from it shape only the back layers and
  /// keep surfaceOffset (the per-particle search costs two sums over 2 r_m each). Unset: every particle.
  std::optional<glm::vec3> eye;
  bool needDensity = true;  ///< False when every particle is an aggregate (liquid.layers = merged).
  /// Shapes remembered for the frame's other views (null: none), for the grid's cloud that the memory holds.
  ShapeMemory* memory = nullptr;

  static AnisotropySettings fromParameters(const LiquidParameters& parameters);
};

/// Weighted sums over a particle's neighbours within R (the particle itself included), with offsets
/// q = (x_j - x_i) / R and Yu and Turk's weight w = 1 - |q|^3.
struct NeighbourMoments {
  float weightSum = 0.0f;                                ///< sum w
  glm::vec3 weightedOffset{0.0f};                        ///< sum w q
  float xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;  ///< sum w q q^T
  float isotropicKernelSum = 0.0f;  ///< sum P(|q|), for the density with the ball of radius R
  int neighbourCount = 0;           ///< Not counting the particle itself.
};

enum class ShapeKind : std::uint8_t {
  Hidden,        ///< Outside the frustum: only a neighbour, not shaped.
  UnderSampled,  ///< Fewer than N_epsilon neighbours (or a degenerate covariance): a sphere of k_n r.
  Interior,      ///< Deep inside the body: a sphere of radius r, no eigen-decomposition.
  Anisotropic,   ///< An ellipsoid from the covariance's principal axes.
};

/// A particle's drawn shape, and the kernel its density is measured with (same axes, larger semi-axes).
struct ParticleShape {
  ShapeKind kind = ShapeKind::UnderSampled;
  glm::vec3 centreOffset{0.0f};  ///< From the particle to the drawn centre (lambda times the weighted mean).
  glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  ///< Unit principal directions.
  glm::vec3 semiAxes{1.0f};                               ///< Drawn semi-axes, world units.
  glm::vec3 kernelSemiAxes{1.0f};  ///< Semi-axes of the density kernel's support, world units.
};

/// The normalised kernel profile P(q) = (1 - q^2)^3 on the unit ball, and its normalisation 315 / (64 pi).
constexpr float kKernelNormalisation = 315.0f / (64.0f * 3.14159265358979f);

/// Each eigenvalue of the weighted covariance, in units of R^2, of a particle inside a body of uniform
/// density: integral of w(d) x^2 over the ball divided by the integral of w(d), with w(d) = 1 - (d/R)^3,
/// = (1/3) (3 R^5 / 40) / (R^3 / 6) = 0.15 R^2. A particle with this covariance gets semi-axes of r.
constexpr float kRestCovariance = 0.15f;

ParticleShape shapeFromMoments(const NeighbourMoments& moments, float radius,
                               const AnisotropySettings& settings);

/// liquid.reach_radius: what an anisotropic shape is grown by, in radii, so that its shortest semi-axis
/// reaches r. A surface particle's ellipsoid is flattened along the surface's normal (its shortest axis), so
/// a flat face of the body then stands where the particles' spheres reach.
float reachRadiusOffset(const ParticleShape& shape, float radius);

/// How far an aggregate may be grown to reach Mantaflow's surface, as a multiple of the flat derivation's
/// offset s (liquid.surface_offset). A cap of s itself held the examples' flat water about 0.3 r below
/// Mantaflow's mesh: a FLIP surface particle's flattened ellipsoid often needs more than a lattice's top
/// layer does to reach it (docs/mantaflow-caches.md, "The offset's cap"). The search's bound is what limits
/// it on the examples (none exceeds 1.5 s); this cap is there for the views' culling margins.
inline constexpr float kMeshOffsetPerFlat = 1.5f;

/// The most any aggregate is grown by, in radii: liquid.surface_offset, what liquid.reach_radius can add
/// (the shortest semi-axis is at least k_n r / k_r), or 1.5 liquid.surface_offset where an aggregate reaches
/// Mantaflow's surface (liquid.mesh_kernel_radius). For bounds that must hold every drawn ellipsoid.
float largestSurfaceOffset(const LiquidParameters& parameters);

/// The ellipsoid instance of a shape: the inverse of the axes matrix (rotation times diag(semi-axes)) is
/// diag(1 / semi-axes) times the transposed rotation, so its rows are the principal directions divided by
/// their semi-axes.
EllipsoidInstance ellipsoidInstance(const glm::vec3& centre, const glm::vec3 axes[3],
                                    const glm::vec3& semiAxes);
EllipsoidInstance sphereInstance(const glm::vec3& centre, float radius);

/// The shapes and densities of the visible particles of a grid, indexed like grid.particles().
struct ParticleShapes {
  std::vector<EllipsoidInstance> instances;
  std::vector<ShapeKind> kinds;
  /// Yu and Turk's density sum_j W(x_j - x_i, G_i) times r^3: neighbours per cubed particle radius, so
  /// unit-free. Zero when the settings do not need densities.
  std::vector<float> densities;
  /// The surface offset each instance was grown by, in radii (liquid.surface_offset, or the per-particle
  /// offset to Mantaflow's surface or to the particle's radius, liquid.reach_radius).
  std::vector<float> offsets;
};

/// What of a particle's shaping no view changes: its shape and density from its neighbours, and where their
/// weighted mean lies (which side faces an eye). With Mantaflow's surface, the offset each view grows the
/// shape by is the view's own (only the particles whose outward side faces its eye search for it).
struct ViewlessShape {
  ParticleShape shape;
  glm::vec3 weightedOffset{0.0f};  ///< NeighbourMoments::weightedOffset.
  float density = 0.0f;            ///< As ParticleShapes::densities.
};

/// Each particle's ViewlessShape, remembered so that the views of one frame (the camera's, every light's, the
/// sky's) shape a particle once: its neighbour sums are most of a view's preparation. Indexed like the
/// sorted cloud of the first view that resets it; an entry is reused only for a particle at the same position
/// with the same radius, so a reused shape is bit for bit the one a new computation would give. The views
/// sharing it shape with the same settings (one frame's parameters). One thread at a time may use an index.
class ShapeMemory {
 public:
  /// Forgets every shape and holds `particles` entries.
  void reset(std::size_t particles) { entries_.assign(particles, Entry{}); }
  std::size_t size() const { return entries_.size(); }
  /// How many particles have a shape remembered.
  std::size_t remembered() const;
  /// The remembered shape of particle `index` at `position` with `radius`, or null.
  const ViewlessShape* find(std::size_t index, const glm::vec3& position, float radius) const;
  void remember(std::size_t index, const glm::vec3& position, float radius, const ViewlessShape& shape);

 private:
  struct Entry {
    glm::vec3 position{0.0f};
    float radius = -1.0f;  // Negative: nothing remembered.
    ViewlessShape shape;
  };
  std::vector<Entry> entries_;
};

/// Shapes every visible particle of the grid from its neighbours (TBB-parallel over cells).
ParticleShapes shapeParticles(const NeighbourGrid& grid, const AnisotropySettings& settings);

}  // namespace spindrift
