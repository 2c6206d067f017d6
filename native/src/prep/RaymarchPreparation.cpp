#include "prep/RaymarchPreparation.h"

#include <algorithm>
#include <cmath>

#include "prep/ViewFrustum.h"

namespace spindrift {

RaymarchGrid fitRaymarchGrid(const glm::vec3& low, const glm::vec3& high, float smoothingRadius) {
  RaymarchGrid grid;
  grid.cellSize = smoothingRadius;
  if (!(low.x <= high.x && low.y <= high.y && low.z <= high.z)) return grid;  // no particles
  // One cell of margin on each side, then round each side up to an even count.
  const glm::vec3 extent = high - low;
  float cellSize = smoothingRadius;
  auto cellsFor = [&](float size) { return glm::ivec3(glm::floor(extent / size)) + 3; };
  auto total = [](glm::ivec3 c) { return double(c.x + 1) * double(c.y + 1) * double(c.z + 1); };
  glm::ivec3 cells = cellsFor(cellSize);
  // A scene much larger than h would need too many cells: grow the cells, which keeps the grid conservative
  // (a larger cell still holds every particle that reaches its points within its 3x3x3 neighbourhood).
  while (total(cells) > double(RaymarchGrid::kMaximumCells)) {
    cellSize *= 1.25f;
    cells = cellsFor(cellSize);
  }
  grid.cellSize = cellSize;
  grid.size = (cells + 1) / 2 * 2;
  grid.origin = low - glm::vec3(cellSize);
  return grid;
}

RaymarchPreparation prepareRaymarch(const Particles& particles, const Camera& camera, float particleRadius,
                                    const LiquidParameters& parameters) {
  RaymarchPreparation preparation;
  preparation.particleRadius = particleRadius;
  preparation.smoothingRadius = parameters.raymarch_smoothing_radius * particleRadius;
  const float support = preparation.smoothingRadius;
  const ViewFrustum frustum(camera);
  glm::vec3 low(INFINITY), high(-INFINITY);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const glm::vec3& position = particles.positions[i];
    const float radius = particles.radii[i];
    if (particles.kinds[i] != ParticleKind::Liquid || !(radius > 0.0f) || !std::isfinite(radius) ||
        !std::isfinite(position.x + position.y + position.z))
      continue;
    if (!frustum.reachedBySphere(frustum.cameraFromWorld(position), support)) continue;
    preparation.particles.emplace_back(position, radius);
    low = glm::min(low, position);
    high = glm::max(high, position);
  }
  preparation.grid = fitRaymarchGrid(low, high, support);
  return preparation;
}

}  // namespace spindrift
