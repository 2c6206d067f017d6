#include "prep/RaymarchPreparation.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "prep/Anisotropy.h"
#include "prep/ViewFrustum.h"
#include "scene/MantaflowDomain.h"

namespace spindrift {
namespace {

// Supports tabulated between liquid.raymarch_smoothing_radius r and the largest an aggregate needs; the
// height is smooth and increasing in the support (about 0.9 per unit), so linear interpolation is ample.
constexpr int kSupportTableSize = 33;
// How far the marched kernels follow an aggregate's offset, as a multiple of the flat offset s; the drawn
// offsets reach up to kMeshOffsetPerFlat s.
constexpr float kMarchedOffsetPerFlat = 1.2f;
static_assert(kMarchedOffsetPerFlat <= kMeshOffsetPerFlat, "the marched kernels follow the drawn offsets");

float kernelProfile(float squaredDistance, float inverseSquaredSupport) {
  const float falloff = 1.0f - squaredDistance * inverseSquaredSupport;
  return falloff > 0.0f ? falloff * falloff * falloff : 0.0f;
}

}  // namespace

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

float flatIsoSurfaceHeight(float support, float spacing, float iso) {
  const int reach = int(std::ceil(support / spacing)) + 1;
  const float inverseSquaredSupport = 1.0f / (support * support);
  const auto density = [&](float height) {
    float sum = 0.0f;
    for (int layer = 0; layer <= reach; ++layer)
      for (int i = -reach; i <= reach; ++i)
        for (int j = -reach; j <= reach; ++j) {
          const float dz = height + float(layer) * spacing, dx = float(i) * spacing, dy = float(j) * spacing;
          sum += kernelProfile(dx * dx + dy * dy + dz * dz, inverseSquaredSupport);
        }
    return sum;
  };
  // At the top particle the density is at least one (above any sensible iso-value), at the support's
  // distance above it zero.
  float inside = 0.0f, outside = support;
  for (int step = 0; step < 32; ++step) {
    const float middle = 0.5f * (inside + outside);
    (density(middle) >= iso ? inside : outside) = middle;
  }
  return inside;
}

RaymarchPreparation prepareRaymarch(const LiquidPreparation& liquid, const Camera& camera,
                                    float particleRadius, const LiquidParameters& parameters,
                                    const DomainBox* domain) {
  RaymarchPreparation preparation;
  if (domain) preparation.domain = *domain;
  preparation.particleRadius = particleRadius;
  const float baseSupport = parameters.raymarch_smoothing_radius * particleRadius;
  const float iso = parameters.raymarch_iso;

  // Aggregates: the drawn flat surface stands kSpindriftFlatOffsetRadii r + o above the top particles. The
  // supports between the base and the one the largest offset needs are tabulated with their flat heights.
  const float spacing = particleRadius / kRadiusPerSpacing;
  float largestOffset = 0.0f;
  // The kernels follow each aggregate's offset up to kMarchedOffsetPerFlat s: the grid's cells are the
  // largest support, so a few larger offsets would widen every cell (on the drop the march read 77 % more
  // particles per ray for 0.03 r of median depth, docs/raymarch.md).
  const float marchedOffset = kMarchedOffsetPerFlat * parameters.surface_offset * particleRadius;
  for (const glm::vec4& aggregate : liquid.marchedAggregates)
    if (std::isfinite(aggregate.w))
      largestOffset = std::max(largestOffset, std::min(aggregate.w, marchedOffset));
  const float highestFlat = kSpindriftFlatOffsetRadii * particleRadius + largestOffset;
  float largestSupport = baseSupport;
  while (flatIsoSurfaceHeight(largestSupport, spacing, iso) < highestFlat &&
         largestSupport < 64.0f * particleRadius)
    largestSupport *= 1.25f;
  std::array<float, kSupportTableSize> supports{}, heights{};
  for (int k = 0; k < kSupportTableSize; ++k) {
    supports[k] = baseSupport + (largestSupport - baseSupport) * float(k) / float(kSupportTableSize - 1);
    heights[k] = flatIsoSurfaceHeight(supports[k], spacing, iso);
  }
  const auto aggregateSupport = [&](float offset) {
    const float height = kSpindriftFlatOffsetRadii * particleRadius + offset;
    if (!(height > heights[0])) return supports[0];
    const auto upper = std::lower_bound(heights.begin(), heights.end(), height);
    if (upper == heights.end()) return supports.back();
    const std::size_t k = std::size_t(upper - heights.begin());
    const float fraction = (height - heights[k - 1]) / std::max(heights[k] - heights[k - 1], 1e-12f);
    return supports[k - 1] + fraction * (supports[k] - supports[k - 1]);
  };
  // Splashes: a lone particle's iso-surface is the sphere where (1 - q^2)^3 = iso.
  const float loneRadiusPerSupport = std::sqrt(std::max(1.0f - std::cbrt(iso), 1e-6f));

  const ViewFrustum frustum(camera);
  glm::vec3 low(INFINITY), high(-INFINITY);
  float largest = baseSupport;
  const auto add = [&](const glm::vec3& position, float support) {
    if (!(support > 0.0f) || !std::isfinite(support) || !std::isfinite(position.x + position.y + position.z))
      return;
    if (!frustum.reachedBySphere(frustum.cameraFromWorld(position), support)) return;
    preparation.particles.emplace_back(position, support);
    low = glm::min(low, position);
    high = glm::max(high, position);
    largest = std::max(largest, support);
  };
  for (const glm::vec4& aggregate : liquid.marchedAggregates)
    add(glm::vec3(aggregate), aggregateSupport(std::clamp(aggregate.w, 0.0f, marchedOffset)));
  // A splash's kernel is capped at the body's largest support: a larger one fuses with the body nearby into a
  // bulge far outside Mantaflow's surface, and would widen every cell. A lone drop larger than the cap keeps
  // its size through its drawn sphere (raymarch_upsample.comp).
  for (const glm::vec4& splash : liquid.marchedSplashes)
    add(glm::vec3(splash), std::min(supports.back(), splash.w / loneRadiusPerSupport));
  preparation.smoothingRadius = largest;
  preparation.grid = fitRaymarchGrid(low, high, largest);
  return preparation;
}

}  // namespace spindrift
