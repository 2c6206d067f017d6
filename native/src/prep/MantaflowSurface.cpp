#include "prep/MantaflowSurface.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace spindrift {
namespace {

// x̄(at) − at, Mantaflow's weighted mean of the particles within `support` (2 r_m) of `at`, with weights
// max(0, 1 − d²/support²), relative to `at`; `found` is false when no particle lies within reach.
glm::vec3 offsetToMean(const NeighbourGrid& grid, const glm::vec3& at, float support,
                       std::vector<IndexRange>& ranges, bool& found) {
  const ParticleCloud& cloud = grid.particles();
  grid.rangesWithin(at.x, at.y, at.z, support, ranges);
  const float inverseSupportSquared = 1.0f / (support * support);
  float sum = 0.0f, sx = 0.0f, sy = 0.0f, sz = 0.0f;
  const float* xs = cloud.x.data();
  const float* ys = cloud.y.data();
  const float* zs = cloud.z.data();
  for (const IndexRange& range : ranges) {
    const int end = int(range.end);
#pragma omp simd reduction(+ : sum, sx, sy, sz)
    for (int j = int(range.begin); j < end; ++j) {
      const float dx = xs[j] - at.x, dy = ys[j] - at.y, dz = zs[j] - at.z;
      const float weight = std::max(0.0f, 1.0f - (dx * dx + dy * dy + dz * dz) * inverseSupportSquared);
      sum += weight;
      sx += weight * dx;
      sy += weight * dy;
      sz += weight * dz;
    }
  }
  found = sum > 0.0f;
  return found ? glm::vec3(sx, sy, sz) / sum : glm::vec3(0.0f);
}

}  // namespace

float mantaflowSurfaceDistance(const NeighbourGrid& grid, std::size_t i, float kernelRadius, float maxRadius,
                               int refinements, std::vector<IndexRange>& ranges, glm::vec3& out) {
  const ParticleCloud& cloud = grid.particles();
  const float support = 2.0f * kernelRadius;
  const glm::vec3 particle(cloud.x[i], cloud.y[i], cloud.z[i]);
  bool found = false;
  const glm::vec3 towardsMean = offsetToMean(grid, particle, support, ranges, found);
  // Out of the body, away from where the neighbours pull; a lone particle's blob is round, any way will do.
  const float pull = glm::length(towardsMean);
  out = pull > 1e-6f * kernelRadius ? -towardsMean / pull : glm::vec3(0.0f, 0.0f, 1.0f);
  float inside = 0.0f, insideValue = pull - kernelRadius;
  if (insideValue >= 0.0f) return 0.0f;
  const auto levelSet = [&](float t) {
    const glm::vec3 at = particle + t * out;
    const glm::vec3 offset = offsetToMean(grid, at, support, ranges, found);
    return found ? glm::length(offset) - kernelRadius : kernelRadius;
  };
  // φ grows by about one per unit along `out` (x̄ moves little): first guess t = −φ(0), then secant steps
  // through the last two points. Over a body one refinement lands within a few hundredths of a radius of the
  // bisected zero (MantaflowSurface tests); a lone particle needs none, as φ is then exactly linear.
  // x̄ follows x outwards (it never moves against it), so φ grows by at most one per unit: the zero lies at
  // least −φ(0) out, and a particle that deep needs no second sum.
  if (-insideValue >= maxRadius) return maxRadius;
  float t = -insideValue;
  for (int step = 0; step <= refinements; ++step) {
    const float value = levelSet(t);
    if (value <= 0.0f && t >= maxRadius) return maxRadius;
    const float slope = (value - insideValue) / (t - inside);
    const float next = slope > 1e-3f ? t - value / slope : maxRadius;
    inside = t;
    insideValue = value;
    t = std::clamp(next, 0.0f, maxRadius);
  }
  return t;
}

}  // namespace spindrift
