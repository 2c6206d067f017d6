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

#include "prep/EllipsoidBounds.h"
#include "prep/LayerOrder.h"

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

// A surface point is hidden only inside a voxel that fits inside another ellipsoid's inscribed ball. Balls
// about the points of a cubic lattice of spacing s leave its cube centres uncovered while their radius is
// below sqrt(3) / 2 s, and every particle's surface passes near one of those gaps: with the median
// inscribed radius below that many spacings the test drops nothing (the light benchmark's lattices, at 0.74,
// dropped none in 10-40 ms a view; the thick tank of docs/frame-cost.md, at 3.3, drops 74 %).
constexpr float kMinInscribedPerSpacing = 0.8660254f;

// Below this fraction of isotropic (deep) aggregates, dropHiddenAggregates does not try.
constexpr double kMinDeepFraction = 0.1;

constexpr std::int32_t kNoOwner = -1;
constexpr std::int32_t kSeveralOwners = -2;

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

// Which layers a domain box may cut an ellipsoid in. The front layer keeps max(entry, box entry): the box
// cuts it only through faces that rays enter by, those whose plane has the eye outside. The back layer keeps
// min(exit, box exit): only faces that rays leave by, those with the eye inside. An ellipsoid whose bounding
// sphere crosses no such face is, in that layer, its own surface inside the box or nothing.
struct DomainCuts {
  bool front = false;
  bool back = false;
};

DomainCuts domainCuts(const EllipsoidInstance& ellipsoid, const DomainBox& domain,
                      const glm::mat4& boxFromWorld, float boxScale, const glm::vec3& eyeInBox) {
  const glm::vec3 centre =
      glm::vec3(boxFromWorld * glm::vec4(glm::vec3(ellipsoid.centreAndBoundingRadius), 1.0f));
  const float reach = ellipsoid.centreAndBoundingRadius.w * boxScale;
  DomainCuts cuts;
  for (int axis = 0; axis < 3; ++axis) {
    if (!(centre[axis] - reach > domain.low[axis])) {
      (eyeInBox[axis] < domain.low[axis] ? cuts.front : cuts.back) = true;
    }
    if (!(centre[axis] + reach < domain.high[axis])) {
      (eyeInBox[axis] > domain.high[axis] ? cuts.front : cuts.back) = true;
    }
  }
  return cuts;
}

// The domain box in the frame the voxels are tested in: its cache-to-world inverse and a bound of its
// stretch.
struct ClipBox {
  glm::mat4 boxFromWorld{1.0f};
  float scale = 1.0f;
  glm::vec3 low{0.0f};
  glm::vec3 high{0.0f};
};

struct HiddenHalves {
  bool front = false;  ///< Every camera-facing point lies inside another ellipsoid: no front pixel to win.
  bool back = false;   ///< Likewise every point facing away: no back pixel to win.
};

// Narrows [from, to] to the voxels of row (y, z) that may reach inside the box (their centres within a half
// diagonal of it, in the box's frame); false when none do.
bool insideBoxSpan(const ClipBox& box, const VoxelGrid& grid, int y, int z, float halfDiagonal, int& from,
                   int& to) {
  const glm::vec3 start = glm::vec3(box.boxFromWorld * glm::vec4(grid.centre(0, y, z), 1.0f));
  const glm::vec3 step = glm::mat3(box.boxFromWorld) * glm::vec3(grid.size, 0.0f, 0.0f);
  const float reach = halfDiagonal * box.scale;
  double low = from, high = to;
  for (int axis = 0; axis < 3; ++axis) {
    const double lowEdge = double(box.low[axis] - reach) - start[axis];
    const double highEdge = double(box.high[axis] + reach) - start[axis];
    if (step[axis] == 0.0f) {
      if (lowEdge > 0.0 || highEdge < 0.0) return false;
      continue;
    }
    double a = lowEdge / step[axis], b = highEdge / step[axis];
    if (a > b) std::swap(a, b);
    low = std::max(low, a - 0.01);  // Rounded outwards: more voxels checked, never fewer.
    high = std::min(high, b + 0.01);
  }
  if (low > high) return false;
  from = std::max(from, int(std::ceil(low)));
  to = std::min(to, int(std::floor(high)));
  return from <= to;
}

// Which halves of the ellipsoid's surface lie inside the covered voxels of other ellipsoids. With M the
// inverse axes (|M (x - c)| = 1 on the surface) the normal at x is Q (x - c), Q = M^T M, and x faces the eye
// e when Q (x - c) . (x - e) < 0, that is (x - c) . m < -1 with m = Q (c - e): the camera-facing half lies
// below a plane through the centre, the far half above the parallel plane (points on the silhouette belong to
// both). x -> |M (x - c)| is Lipschitz with the largest singular value s = 1 / inscribed, so a voxel of half
// diagonal h touches the surface only where 1 - h s <= |M (v - c)| <= 1 + h s at its centre v, and a half
// only where (v - c) . m is within h |m| of that half's side.
//
// With a domain box, surface points outside it do not count: a half is a candidate only where the box cuts
// the other layer (domainCuts), and there a point outside the box is never reached by a ray of this layer
// while the ray is inside the box.
HiddenHalves hiddenHalves(const EllipsoidInstance& ellipsoid, std::int32_t self, float inscribed,
                          const glm::vec3& eye, const VoxelGrid& grid, HiddenHalves candidates,
                          const ClipBox* box) {
  const glm::vec3 centre(ellipsoid.centreAndBoundingRadius);
  const glm::mat3 rows = glm::transpose(glm::mat3(glm::vec3(ellipsoid.inverseAxesRows[0]),
                                                  glm::vec3(ellipsoid.inverseAxesRows[1]),
                                                  glm::vec3(ellipsoid.inverseAxesRows[2])));
  const glm::vec3 facing = glm::transpose(rows) * (rows * (centre - eye));
  const float halfDiagonal = 0.5f * std::sqrt(3.0f) * grid.size;
  // The voxel's reach, and rounding in the offsets (a ten-thousandth of the ellipsoid's size).
  const float facingSlack =
      (halfDiagonal + 1e-4f * ellipsoid.centreAndBoundingRadius.w) * glm::length(facing);
  const auto covered = [&](std::int32_t owner) { return owner != kNoOwner && owner != self; };
  HiddenHalves halves = candidates;
  if (!halves.front && !halves.back) return halves;
  const auto uncover = [&](float side) {
    if (side <= -1.0f + facingSlack) halves.front = false;
    if (side >= -1.0f - facingSlack) halves.back = false;
  };

  // The six ends of the axes lie on the surface: a particle at the surface usually shows an uncovered half
  // on one of them, before the neighbourhood is scanned (ends outside the box are left to the scan).
  for (int k = 0; k < 6; ++k) {
    const glm::vec3 row(ellipsoid.inverseAxesRows[k / 2]);
    const glm::vec3 offset = (k % 2 ? -1.0f : 1.0f) * row / glm::dot(row, row);
    if (box) {
      const glm::vec3 end = glm::vec3(box->boxFromWorld * glm::vec4(centre + offset, 1.0f));
      if (glm::any(glm::lessThan(end, box->low)) || glm::any(glm::greaterThan(end, box->high))) continue;
    }
    const glm::ivec3 voxel = glm::clamp(glm::ivec3(glm::floor((centre + offset - grid.low) / grid.size)),
                                        glm::ivec3(0), grid.dims - 1);
    if (!covered(grid.owners[grid.index(voxel.x, voxel.y, voxel.z)].load(std::memory_order_relaxed)))
      uncover(glm::dot(offset, facing));
  }
  if (!halves.front && !halves.back) return halves;

  // The shell of voxels that may touch the surface, row by row: along a row of voxel centres v(x) = v0 + x d,
  // |M (v - c)|^2 is a quadratic in x, so each row's shell is an outer interval less an inner one.
  const float slack = halfDiagonal / inscribed + 1e-4f;
  const double outer = double(1.0f + slack) * (1.0f + slack);
  const double inner = slack < 1.0f ? double(1.0f - slack) * (1.0f - slack) : -1.0;
  const glm::vec3 step = rows * glm::vec3(grid.size, 0.0f, 0.0f);
  const double a = glm::dot(step, step);
  const auto interval = [&](double b, double c, double limit, double& low, double& high) {
    const double discriminant = b * b - 4.0 * a * (c - limit);
    if (discriminant < 0.0) return false;
    const double root = std::sqrt(discriminant);
    low = (-b - root) / (2.0 * a);
    high = (-b + root) / (2.0 * a);
    return true;
  };
  glm::ivec3 first, last;
  grid.range(centre, ellipsoid.centreAndBoundingRadius.w + halfDiagonal, first, last);
  for (int z = first.z; z <= last.z; ++z) {
    for (int y = first.y; y <= last.y; ++y) {
      const glm::vec3 rowStart = grid.centre(0, y, z) - centre;
      const glm::vec3 mapped = rows * rowStart;
      const double b = 2.0 * glm::dot(step, mapped), c = glm::dot(mapped, mapped);
      double outerLow, outerHigh;
      if (!interval(b, c, outer, outerLow, outerHigh)) continue;
      // Rounded outwards by a hundredth of a voxel: more voxels checked, never fewer.
      // Clamped before the conversion: a degenerate quadric gives infinities, which no int holds (a NaN
      // keeps the whole row, which only checks more voxels).
      const int from = int(std::max<double>(first.x, std::ceil(outerLow - 0.01)));
      const int to = int(std::min<double>(last.x, std::floor(outerHigh + 0.01)));
      double innerLow = 1.0, innerHigh = 0.0;  // Empty unless the row passes through the core.
      if (inner > 0.0 && interval(b, c, inner, innerLow, innerHigh)) {
        innerLow += 0.01;
        innerHigh -= 0.01;
      }
      int boxFrom = from, boxTo = to;
      if (box && !insideBoxSpan(*box, grid, y, z, halfDiagonal, boxFrom, boxTo)) continue;
      const float sideStart = glm::dot(rowStart, facing), sideStep = grid.size * facing.x;
      for (int x = boxFrom; x <= boxTo; ++x) {
        if (x > innerLow && x < innerHigh) continue;
        if (covered(grid.owners[grid.index(x, y, z)].load(std::memory_order_relaxed))) continue;
        uncover(sideStart + float(x) * sideStep);
        if (!halves.front && !halves.back) return halves;
      }
    }
  }
  return halves;
}
}  // namespace

HiddenInteriorResult dropHiddenInterior(std::vector<EllipsoidInstance>& ellipsoids, const Camera& camera,
                                        const DomainBox* domain, const SolidDepthTiles* solids,
                                        float particleSpacing) {
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
    inscribed[i] = inscribedRadius(ellipsoids[i]);
    const glm::vec4& sphere = ellipsoids[i].centreAndBoundingRadius;
    low = glm::min(low, glm::vec3(sphere) - sphere.w);
    high = glm::max(high, glm::vec3(sphere) + sphere.w);
  }
  std::vector<float> sorted = inscribed;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(count / 2), sorted.end());
  const float medianInscribed = sorted[count / 2];
  if (medianInscribed < kMinInscribedPerSpacing * particleSpacing) {
    result.notApplied = "the ellipsoids' inscribed balls cannot cover each other (median radius " +
                        std::to_string(medianInscribed / particleSpacing) + " of the particles' spacing)";
    return result;
  }
  VoxelGrid grid;
  grid.size = medianInscribed / kVoxelsPerInscribedRadius;
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

  ClipBox box;
  if (domain) {
    box.boxFromWorld = glm::inverse(domain->worldFromBox);
    box.scale = stretchBound(glm::mat3(box.boxFromWorld));
    box.low = domain->low;
    box.high = domain->high;
  }
  const glm::mat4& boxFromWorld = box.boxFromWorld;
  const float boxScale = box.scale;
  const glm::vec3 eye = camera.position();
  const glm::vec3 eyeInBox = glm::vec3(boxFromWorld * glm::vec4(eye, 1.0f));
  std::vector<HiddenHalves> hidden(count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const EllipsoidInstance& ellipsoid = ellipsoids[i];
      // Which halves may be hidden: not where the domain box cuts the layer's surface, and in the back layer
      // not where a solid may lie in front of the ellipsoid's far side. (A solid hides a fragment whose entry
      // lies behind it; the ellipsoid that holds a front entry point entered earlier and is not hidden, but
      // the one that holds an exit point may have entered behind the solid.)
      HiddenHalves candidates{true, true};
      if (domain) {
        const DomainCuts cuts = domainCuts(ellipsoid, *domain, boxFromWorld, boxScale, eyeInBox);
        candidates = {!cuts.front, !cuts.back};
      }
      const glm::vec3 centre(ellipsoid.centreAndBoundingRadius);
      if (candidates.back && solids &&
          solids->solidNearerThan(centre, ellipsoid.centreAndBoundingRadius.w, depths[i]))
        candidates.back = false;
      hidden[i] = hiddenHalves(ellipsoid, std::int32_t(i), inscribed[i], eye, grid, candidates,
                               domain ? &box : nullptr);
    }
  });

  std::vector<char> inFront(count), inBack(count);
  for (std::size_t i = 0; i < count; ++i) {
    inFront[i] = !hidden[i].front;
    inBack[i] = !hidden[i].back;
  }
  result.split = orderByLayers(ellipsoids, inFront, inBack);
  result.dropped = count - ellipsoids.size();
  result.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

bool manyDeepAggregates(const LiquidPreparation& liquid) {
  return double(liquid.isotropicInterior) >= kMinDeepFraction * double(liquid.aggregates.size());
}

HiddenInteriorResult dropHiddenAggregates(LiquidPreparation& liquid, const Camera& camera,
                                          const DomainBox* domain, const SolidDepthTiles* solidTiles,
                                          OcclusionWorkspace* workspace) {
  // Deep particles are the ones the anisotropy found isotropic; where they are few the body is a sheet or a
  // spray, which hides little: on the dam-break example (5 % deep) 0.8 % of the aggregates are hidden from
  // both layers and 6 % from one, fewer fragments than the grid's cost on the CPU (docs/frame-cost.md).
  HiddenInteriorResult result;
  if (!manyDeepAggregates(liquid)) {
    result.notApplied = "few deep aggregates (" + std::to_string(liquid.isotropicInterior) + " of " +
                        std::to_string(liquid.aggregates.size()) + ")";
  } else {
    result = dropHiddenInterior(liquid.aggregates, camera, domain, solidTiles, liquid.particleSpacing);
  }
  liquid.aggregateLayers = result.split;
  // What the view hides: the body's far side behind its near side, and the inside of a body whose particles
  // leave gaps between them.
  result.occluded = dropOccludedAggregates(liquid.aggregates, liquid.aggregateLayers, camera, domain,
                                           solidTiles, workspace);
  return result;
}

}  // namespace spindrift
