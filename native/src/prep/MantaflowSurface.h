#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "prep/NeighbourGrid.h"

namespace spindrift {

/// Mantaflow's averaged (Zhu–Bridson) particle level set φ(x) = |x − x̄(x)| − r_m, x̄ the mean of the liquid
/// particles within 2 r_m of x weighted by max(0, 1 − d²/(2 r_m)²) (docs/mantaflow-caches.md), over a cloud
/// whose particles are lumped per cell of r_m / 2 of a dense grid: each cell counts as its particles at their
/// centroid. A sum over the 2 r_m ball then reads a few hundred cells in contiguous runs instead of about
/// 1,400 particles; the tests bound what the lumping moves the surface. The concavity correction (c ≤ 1) and
/// the mesh smoothing are left out: both only matter where the surface is concave or curved within a few
/// cells.
class MantaflowLevelSet {
 public:
  MantaflowLevelSet(const ParticleCloud& cloud, float kernelRadius);

  float kernelRadius() const { return kernelRadius_; }

  /// x̄(at) − at; false (and 0) when no particle lies within 2 r_m.
  bool offsetToMean(const glm::vec3& at, glm::vec3& offset) const;

  /// How far Mantaflow's mesh reaches out from a particle at `particle`, in world units: 0 when the particle
  /// lies outside the surface (its neighbours pull x̄ more than r_m away: Mantaflow draws no bump for it, the
  /// body's surface passes near it), else the distance to φ = 0 along `out`, the direction away from
  /// x̄(particle), at most `maxRadius`. A lone particle gets r_m. Found by secant steps (`refinements` after
  /// the first guess, each one more sum).
  float surfaceDistance(const glm::vec3& particle, float maxRadius, int refinements, glm::vec3& out) const;

 private:
  float kernelRadius_;
  float cellSize_;
  glm::vec3 origin_{0.0f};
  int cells_[3] = {0, 0, 0};
  // Per cell, z fastest: the particle count and the centroid (0 where empty).
  std::vector<float> count_, centroidX_, centroidY_, centroidZ_;
};

}  // namespace spindrift
