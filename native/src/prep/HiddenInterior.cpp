#include "prep/HiddenInterior.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/glm.hpp>

namespace spindrift {
namespace {

// Voxels per inscribed-ball radius of the median ellipsoid: finer voxels fit better inside the balls (more
// ellipsoids dropped near the surface) but cost more to mark and test. 3 covers the body of an example whose
// drawn particles overlap by a few radii (docs/frame-cost.md has the measurement).
constexpr float kVoxelsPerInscribedRadius = 3.0f;
// The grid never has more voxels than this (64 MiB of owners); coarser voxels only drop fewer ellipsoids.
constexpr double kMaxVoxels = double(1 << 24);
// Fewer ellipsoids than this are drawn as they are: the grid would cost more than it saves.
constexpr std::size_t kMinEllipsoids = 256;

// Below this fraction of isotropic (deep) aggregates, dropHiddenAggregates does not try.
constexpr double kMinDeepFraction = 0.1;

constexpr std::int32_t kNoOwner = -1;
constexpr std::int32_t kSeveralOwners = -2;

// The largest singular value of the matrix whose rows are given, bounded from above by Gershgorin's theorem
// on M M^T: exact for orthogonal rows (an ellipsoid's), and never smaller than the true value, which keeps
// both of its uses below conservative.
float largestSingularValue(const EllipsoidInstance& ellipsoid) {
  float largest = 0.0f;
  for (int i = 0; i < 3; ++i) {
    float rowSum = 0.0f;
    for (int j = 0; j < 3; ++j)
      rowSum += std::abs(
          glm::dot(glm::vec3(ellipsoid.inverseAxesRows[i]), glm::vec3(ellipsoid.inverseAxesRows[j])));
    largest = std::max(largest, rowSum);
  }
  return std::sqrt(largest);
}

struct VoxelGrid {
  glm::vec3 low{0.0f};
  float size = 1.0f;
  glm::ivec3 dims{0};
  std::unique_ptr<std::atomic<std::int32_t>[]> owners;

  std::size_t index(int x, int y, int z) const { return (std::size_t(z) * dims.y + y) * dims.x + x; }
  glm::vec3 centre(int x, int y, int z) const { return low + (glm::vec3(x, y, z) + 0.5f) * size; }
  // The voxel index range (inclusive) whose voxels may hold points within `reach` of `point`.
  void range(const glm::vec3& point, float reach, glm::ivec3& first, glm::ivec3& last) const {
    first = glm::max(glm::ivec3(glm::floor((point - reach - low) / size)), glm::ivec3(0));
    last = glm::min(glm::ivec3(glm::floor((point + reach - low) / size)), dims - 1);
  }
};

// The farthest planar eye depth each ellipsoid's bounding sphere reaches; false when one of them reaches the
// near or far clip plane.
bool farthestDepths(const std::vector<EllipsoidInstance>& ellipsoids, const Camera& camera,
                    std::vector<float>& depths) {
  const glm::mat4 cameraFromWorld = camera.cameraFromWorld();
  depths.resize(ellipsoids.size());
  for (std::size_t i = 0; i < ellipsoids.size(); ++i) {
    const glm::vec4& sphere = ellipsoids[i].centreAndBoundingRadius;
    const float depth = -(cameraFromWorld * glm::vec4(glm::vec3(sphere), 1.0f)).z;
    if (!(depth - sphere.w > camera.nearClip) || !(depth + sphere.w < camera.farClip)) return false;
    depths[i] = depth + sphere.w;
  }
  return true;
}

// Whether the ellipsoid's bounding sphere lies strictly inside the domain box, which then does not cut it.
bool insideDomain(const EllipsoidInstance& ellipsoid, const DomainBox& domain, const glm::mat4& boxFromWorld,
                  float boxScale) {
  const glm::vec3 centre =
      glm::vec3(boxFromWorld * glm::vec4(glm::vec3(ellipsoid.centreAndBoundingRadius), 1.0f));
  const float reach = ellipsoid.centreAndBoundingRadius.w * boxScale;
  return glm::all(glm::greaterThan(centre - reach, domain.low)) &&
         glm::all(glm::lessThan(centre + reach, domain.high));
}

}  // namespace

HiddenInteriorResult dropHiddenInterior(std::vector<EllipsoidInstance>& ellipsoids, const Camera& camera,
                                        const DomainBox* domain, const SolidDepthTiles* solids) {
  const auto start = std::chrono::steady_clock::now();
  HiddenInteriorResult result;
  const std::size_t count = ellipsoids.size();
  if (count < kMinEllipsoids) {
    result.notApplied = "fewer than " + std::to_string(kMinEllipsoids) + " aggregates";
    return result;
  }
  std::vector<float> depths;
  if (!farthestDepths(ellipsoids, camera, depths)) {
    result.notApplied = "the body reaches the near or far clip plane";
    return result;
  }

  std::vector<float> inscribed(count);
  glm::vec3 low(INFINITY), high(-INFINITY);
  for (std::size_t i = 0; i < count; ++i) {
    inscribed[i] = 1.0f / largestSingularValue(ellipsoids[i]);
    const glm::vec4& sphere = ellipsoids[i].centreAndBoundingRadius;
    low = glm::min(low, glm::vec3(sphere) - sphere.w);
    high = glm::max(high, glm::vec3(sphere) + sphere.w);
  }
  std::vector<float> sorted = inscribed;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(count / 2), sorted.end());
  VoxelGrid grid;
  grid.size = sorted[count / 2] / kVoxelsPerInscribedRadius;
  const glm::vec3 extent = high - low;
  const double voxels =
      double(extent.x / grid.size + 3) * (extent.y / grid.size + 3) * (extent.z / grid.size + 3);
  if (!(grid.size > 0.0f) || !std::isfinite(voxels)) {
    result.notApplied = "degenerate ellipsoids";
    return result;
  }
  if (voxels > kMaxVoxels) grid.size *= float(std::cbrt(voxels / kMaxVoxels)) * 1.01f;
  grid.low = low - grid.size;
  grid.dims = glm::ivec3(glm::ceil(extent / grid.size)) + 2;
  const std::size_t voxelCount = std::size_t(grid.dims.x) * grid.dims.y * grid.dims.z;
  grid.owners.reset(new std::atomic<std::int32_t>[voxelCount]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, voxelCount),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t v = r.begin(); v != r.end(); ++v)
                        grid.owners[v].store(kNoOwner, std::memory_order_relaxed);
                    });
  const float halfDiagonal = 0.5f * std::sqrt(3.0f) * grid.size;

  // Mark each voxel that fits inside an ellipsoid's inscribed ball with that ellipsoid, or as held by
  // several. The final state of a voxel does not depend on the order of the claims, so neither does the
  // result.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const glm::vec3 centre(ellipsoids[i].centreAndBoundingRadius);
      const float reach =
          inscribed[i] * (1.0f - 1e-5f) - halfDiagonal;  // The voxel's corners inside, strictly.
      if (!(reach > 0.0f)) continue;
      glm::ivec3 first, last;
      grid.range(centre, reach, first, last);
      for (int z = first.z; z <= last.z; ++z)
        for (int y = first.y; y <= last.y; ++y)
          for (int x = first.x; x <= last.x; ++x) {
            const glm::vec3 offset = grid.centre(x, y, z) - centre;
            if (glm::dot(offset, offset) >= reach * reach) continue;
            std::atomic<std::int32_t>& owner = grid.owners[grid.index(x, y, z)];
            std::int32_t seen = kNoOwner;
            if (!owner.compare_exchange_strong(seen, std::int32_t(i), std::memory_order_relaxed) &&
                seen != std::int32_t(i) && seen != kSeveralOwners)
              owner.store(kSeveralOwners, std::memory_order_relaxed);
          }
    }
  });

  // An ellipsoid is hidden when every voxel that may touch it is covered by another ellipsoid. x -> |M x| is
  // Lipschitz with the largest singular value of M, so a voxel whose centre has |M (v - c)| above
  // 1 + halfDiagonal / inscribed holds no point of the ellipsoid.
  glm::mat4 boxFromWorld(1.0f);
  float boxScale = 1.0f;
  if (domain) {
    boxFromWorld = glm::inverse(domain->worldFromBox);
    const glm::mat3 linear(boxFromWorld);
    boxScale = std::sqrt(glm::dot(linear[0], linear[0]) + glm::dot(linear[1], linear[1]) +
                         glm::dot(linear[2], linear[2]));  // Frobenius: at least the largest stretch.
  }
  std::vector<std::uint8_t> hidden(count, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const EllipsoidInstance& ellipsoid = ellipsoids[i];
      if (domain && !insideDomain(ellipsoid, *domain, boxFromWorld, boxScale)) continue;
      const glm::vec3 centre(ellipsoid.centreAndBoundingRadius);
      if (solids && solids->solidNearerThan(centre, ellipsoid.centreAndBoundingRadius.w, depths[i])) continue;
      const glm::mat3 rows = glm::transpose(glm::mat3(glm::vec3(ellipsoid.inverseAxesRows[0]),
                                                      glm::vec3(ellipsoid.inverseAxesRows[1]),
                                                      glm::vec3(ellipsoid.inverseAxesRows[2])));
      const float touchLimit = 1.0f + halfDiagonal / inscribed[i] + 1e-4f;
      // The six ends of the axes lie on the ellipsoid: a particle at the surface usually fails on one of
      // them, before the whole neighbourhood is scanned.
      bool endUncovered = false;
      for (int k = 0; k < 6 && !endUncovered; ++k) {
        const glm::vec3 row(ellipsoid.inverseAxesRows[k / 2]);
        const glm::vec3 end = centre + (k % 2 ? -1.0f : 1.0f) * row / glm::dot(row, row);
        const glm::ivec3 voxel =
            glm::clamp(glm::ivec3(glm::floor((end - grid.low) / grid.size)), glm::ivec3(0), grid.dims - 1);
        const std::int32_t owner =
            grid.owners[grid.index(voxel.x, voxel.y, voxel.z)].load(std::memory_order_relaxed);
        endUncovered = owner == kNoOwner || owner == std::int32_t(i);
      }
      if (endUncovered) continue;
      glm::ivec3 first, last;
      grid.range(centre, ellipsoid.centreAndBoundingRadius.w + halfDiagonal, first, last);
      bool covered = true;
      for (int z = first.z; z <= last.z && covered; ++z)
        for (int y = first.y; y <= last.y && covered; ++y)
          for (int x = first.x; x <= last.x; ++x) {
            const glm::vec3 scaled = rows * (grid.centre(x, y, z) - centre);
            if (glm::dot(scaled, scaled) > touchLimit * touchLimit) continue;
            const std::int32_t owner = grid.owners[grid.index(x, y, z)].load(std::memory_order_relaxed);
            if (owner == kNoOwner || owner == std::int32_t(i)) {
              covered = false;
              break;
            }
          }
      hidden[i] = covered;
    }
  });

  std::size_t kept = 0;
  for (std::size_t i = 0; i < count; ++i)
    if (!hidden[i]) ellipsoids[kept++] = ellipsoids[i];
  result.dropped = count - kept;
  ellipsoids.resize(kept);
  result.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

HiddenInteriorResult dropHiddenAggregates(LiquidPreparation& liquid, const Camera& camera,
                                          const DomainBox* domain,
                                          const std::function<SolidDepthTiles()>& solids) {
  // Deep particles are the ones the anisotropy found isotropic; where they are few the body is a sheet or a
  // spray, which hides almost nothing (the dam-break example: 5 % deep, 0.8 % hidden), and the grid's cost
  // would be lost.
  if (double(liquid.isotropicInterior) < kMinDeepFraction * double(liquid.aggregates.size())) {
    HiddenInteriorResult result;
    result.notApplied = "few deep aggregates (" + std::to_string(liquid.isotropicInterior) + " of " +
                        std::to_string(liquid.aggregates.size()) + ")";
    return result;
  }
  if (!solids) return dropHiddenInterior(liquid.aggregates, camera, domain);
  const SolidDepthTiles tiles = solids();
  return dropHiddenInterior(liquid.aggregates, camera, domain, &tiles);
}

}  // namespace spindrift
