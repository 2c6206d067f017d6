#include "prep/MantaflowSurface.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "spindrift/Error.h"

namespace spindrift {
namespace {

// The dense grid's size limit (4 floats a cell: 256 MiB); a wider scene gets coarser cells, which only lumps
// more particles together.
constexpr double kMaxCells = double(1 << 24);

// A search for φ = 0 has converged where |φ| is below this many kernel radii (a millionth of a particle
// radius and less: float's rounding of the sums).
constexpr float kConverged = 1e-6f;

}  // namespace

MantaflowLevelSet::MantaflowLevelSet(const ParticleCloud& cloud, float kernelRadius)
    : kernelRadius_(kernelRadius), cellSize_(0.5f * kernelRadius) {
  if (!(kernelRadius > 0.0f) || !std::isfinite(kernelRadius))
    throw Error("Mantaflow level set: invalid radius");
  if (cloud.size() == 0) return;
  glm::vec3 lower(cloud.x[0], cloud.y[0], cloud.z[0]), upper = lower;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const glm::vec3 p(cloud.x[i], cloud.y[i], cloud.z[i]);
    lower = glm::min(lower, p);
    upper = glm::max(upper, p);
  }
  origin_ = lower;
  for (;;) {
    double product = 1.0;
    for (int axis = 0; axis < 3; ++axis) {
      cellCounts_[axis] = int(std::floor((upper[axis] - lower[axis]) / cellSize_)) + 1;
      product *= double(cellCounts_[axis]);
    }
    if (product <= kMaxCells) break;
    cellSize_ *= 2.0f;
  }
  const std::size_t columns = std::size_t(cellCounts_[0]) * std::size_t(cellCounts_[1]);
  cells_.assign(columns * std::size_t(cellCounts_[2]), Float4{0.0f, 0.0f, 0.0f, 0.0f});
  occupiedLow_.assign(columns, cellCounts_[2]);
  occupiedHigh_.assign(columns, -1);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    int index[3];
    const float position[3] = {cloud.x[i], cloud.y[i], cloud.z[i]};
    for (int axis = 0; axis < 3; ++axis)
      index[axis] = std::clamp(int((position[axis] - origin_[axis]) / cellSize_), 0, cellCounts_[axis] - 1);
    const std::size_t column = std::size_t(index[0]) * std::size_t(cellCounts_[1]) + std::size_t(index[1]);
    cells_[column * std::size_t(cellCounts_[2]) + std::size_t(index[2])] +=
        Float4{position[0], position[1], position[2], 1.0f};
    occupiedLow_[column] = std::min(occupiedLow_[column], index[2]);
    occupiedHigh_[column] = std::max(occupiedHigh_[column], index[2]);
  }
  for (Float4& cell : cells_) {
    const float count = cell[3];
    if (count == 0.0f) continue;
    cell /= Float4{count, count, count, 1.0f};
  }

  if (cellSize_ != 0.5f * kernelRadius_) return;
  nodeSpacing_ = cellSize_;
  const glm::vec3 support(2.0f * kernelRadius_);
  nodeLow_ = glm::ivec3(glm::floor((lower - support) / nodeSpacing_));
  nodeCounts_ = glm::ivec3(glm::floor((upper + support) / nodeSpacing_)) + 2 - nodeLow_;
  const double nodeCount = double(nodeCounts_.x) * double(nodeCounts_.y) * double(nodeCounts_.z);
  if (nodeCount > kMaxCells) return;
  nodes_.reset(new Float4[std::size_t(nodeCount)]);
  nodeStates_.reset(new std::atomic<std::uint8_t>[std::size_t(nodeCount)]());
}

MantaflowLevelSet::Float4 MantaflowLevelSet::nodeOffset(const glm::ivec3& node) const {
  const std::size_t index =
      (std::size_t(node.x) * std::size_t(nodeCounts_.y) + std::size_t(node.y)) * std::size_t(nodeCounts_.z) +
      std::size_t(node.z);
  std::atomic<std::uint8_t>& state = nodeStates_[index];
  if (state.load(std::memory_order_acquire) == 2) return nodes_[index];
  glm::vec3 offset;
  const bool near = offsetToMean(nodeSpacing_ * glm::vec3(nodeLow_ + node), offset);
  const Float4 value{offset.x, offset.y, offset.z, near ? 1.0f : 0.0f};
  // Another thread summing the same node gets the same value and keeps it to itself.
  std::uint8_t unsummed = 0;
  if (state.compare_exchange_strong(unsummed, 1, std::memory_order_relaxed)) {
    nodes_[index] = value;
    state.store(2, std::memory_order_release);
  }
  return value;
}

bool MantaflowLevelSet::sampledOffsetToMean(const glm::vec3& at, glm::vec3& offset) const {
  if (!nodes_) return offsetToMean(at, offset);
  offset = glm::vec3(0.0f);
  const glm::vec3 lattice = at / nodeSpacing_ - glm::vec3(nodeLow_);
  // Outside the lattice no particle lies within 2 r_m.
  if (!glm::all(glm::greaterThanEqual(lattice, glm::vec3(0.0f))) ||
      !glm::all(glm::lessThan(lattice, glm::vec3(nodeCounts_ - 1))))
    return false;
  const glm::ivec3 base = glm::min(glm::ivec3(lattice), nodeCounts_ - 2);
  const glm::vec3 weight = lattice - glm::vec3(base);
  Float4 sum{0.0f, 0.0f, 0.0f, 0.0f};
  float near = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 step(corner >> 2, (corner >> 1) & 1, corner & 1);
    const glm::vec3 along = glm::mix(glm::vec3(1.0f) - weight, weight, glm::vec3(step));
    const Float4 value = nodeOffset(base + step);
    sum += (along.x * along.y * along.z) * value;
    near += value[3];
  }
  if (near == 0.0f) return false;
  if (near < 8.0f) return offsetToMean(at, offset);
  // x − x_corner interpolates to 0, so the corners' x̄ − x_corner interpolate to x̄ − x.
  offset = glm::vec3(sum[0], sum[1], sum[2]);
  return true;
}

bool MantaflowLevelSet::offsetToMean(const glm::vec3& at, glm::vec3& offset) const {
  const float support = 2.0f * kernelRadius_;
  const float inverseSupportSquared = 1.0f / (support * support);
  const float inverseCell = 1.0f / cellSize_;
  // A centroid lies in its cell, so the cells the support ball touches hold every centroid within it; per
  // column only the run of cells the ball's chord spans, and that holds particles, is read. A cell below
  // 0 along an axis clamps to 0 whether truncated or floored, so truncation does.
  const auto cellOf = [&](float value, int axis) {
    return std::clamp(int((value - origin_[axis]) * inverseCell), 0, cellCounts_[axis] - 1);
  };
  const auto gap = [&](int cell, int axis) {
    const float low = origin_[axis] + float(cell) * cellSize_;
    return std::max({0.0f, low - at[axis], at[axis] - (low + cellSize_)});
  };
  const int x0 = cellOf(at.x - support, 0), x1 = cellOf(at.x + support, 0);
  const int y0 = cellOf(at.y - support, 1), y1 = cellOf(at.y + support, 1);
  // The ball spans at most 4 r_m / cell + 2 cells along y (10 at r_m / 2); a coarsened grid spans fewer.
  float gapYSquared[16];
  const int spanY = std::min(y1 - y0 + 1, 16);
  for (int iy = 0; iy < spanY; ++iy) {
    const float gapY = gap(y0 + iy, 1);
    gapYSquared[iy] = gapY * gapY;
  }
  // Each lane sums in the order of the cells, as four scalar sums would: (x, y, z) weight times offset, and
  // the weight.
  const Float4 centre{at.x, at.y, at.z, 0.0f};
  const Float4 offsetLanes{1.0f, 1.0f, 1.0f, 0.0f}, weightLane{0.0f, 0.0f, 0.0f, 1.0f};
  Float4 sums{0.0f, 0.0f, 0.0f, 0.0f};
  for (int ix = x0; ix <= x1; ++ix) {
    const float gapX = gap(ix, 0);
    for (int iy = y0; iy <= y1; ++iy) {
      const std::size_t column = std::size_t(ix) * std::size_t(cellCounts_[1]) + std::size_t(iy);
      if (occupiedLow_[column] > occupiedHigh_[column]) continue;
      const float chordSquared =
          support * support - gapX * gapX - (iy - y0 < 16 ? gapYSquared[iy - y0] : gap(iy, 1) * gap(iy, 1));
      if (chordSquared < 0.0f) continue;
      const float chord = std::sqrt(chordSquared);
      const int z0 = std::max(cellOf(at.z - chord, 2), occupiedLow_[column]);
      const int z1 = std::min(cellOf(at.z + chord, 2), occupiedHigh_[column]);
      const Float4* run = cells_.data() + column * std::size_t(cellCounts_[2]);
      for (int iz = z0; iz <= z1; ++iz) {
        const Float4 difference = run[iz] - centre;
        const float distanceSquared =
            difference[0] * difference[0] + difference[1] * difference[1] + difference[2] * difference[2];
        // max(0, falloff) as a vector select: the compiler branches on the scalar form.
        const Float4 falloff =
            Float4{0.0f, 0.0f, 0.0f, 0.0f} + (1.0f - distanceSquared * inverseSupportSquared);
        const Float4 weight = run[iz][3] * (falloff > 0.0f ? falloff : Float4{0.0f, 0.0f, 0.0f, 0.0f});
        sums += weight * (difference * offsetLanes + weightLane);
      }
    }
  }
  const float sum = sums[3];
  offset = sum > 0.0f ? glm::vec3(sums[0], sums[1], sums[2]) / sum : glm::vec3(0.0f);
  return sum > 0.0f;
}

float MantaflowLevelSet::surfaceDistance(const glm::vec3& particle, float maxRadius, int refinements,
                                         glm::vec3& out) const {
  glm::vec3 towardsMean;
  sampledOffsetToMean(particle, towardsMean);
  const float pull = glm::length(towardsMean);
  out = outwardFrom(towardsMean, pull);
  return reachAlong(particle, pull, out, maxRadius, refinements);
}

float MantaflowLevelSet::inscribedRadius(const glm::vec3& particle, float maxRadius, int refinements) const {
  glm::vec3 towardsMean;
  sampledOffsetToMean(particle, towardsMean);
  const float pull = glm::length(towardsMean);
  const glm::vec3 out = outwardFrom(towardsMean, pull);
  float least = reachAlong(particle, pull, out, maxRadius, refinements);
  if (!(least > 0.0f)) return 0.0f;
  // A particle in a sheet or a filament has its neighbours' mean almost on itself, so `out` may run along the
  // sheet, where the surface lies far: its blob is as thin as the sheet, which another direction finds.
  const glm::vec3 helper = std::abs(out.x) < 0.7f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::vec3 u = glm::normalize(glm::cross(out, helper)), v = glm::cross(out, u);
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c) {
        if ((a == 0 && b == 0 && c == 0) || (a == 1 && b == 0 && c == 0)) continue;  // `out` is searched
        const glm::vec3 direction = glm::normalize(float(a) * out + float(b) * u + float(c) * v);
        // Bounded by the least so far: a search that gets there stops.
        least = std::min(least, reachAlong(particle, pull, direction, least, refinements));
      }
  return least;
}

glm::vec3 MantaflowLevelSet::outwardFrom(const glm::vec3& towardsMean, float pull) const {
  // Out of the body, away from where the neighbours pull; a lone particle's blob is round, any way will do.
  return pull > 1e-6f * kernelRadius_ ? -towardsMean / pull : glm::vec3(0.0f, 0.0f, 1.0f);
}

float MantaflowLevelSet::reachAlong(const glm::vec3& particle, float pull, const glm::vec3& direction,
                                    float maxRadius, int refinements) const {
  float inside = 0.0f, insideValue = pull - kernelRadius_;
  if (insideValue >= 0.0f) return 0.0f;
  // x̄ follows x outwards (it never moves against it), so φ grows by at most one per unit: the zero lies at
  // least −φ(0) out, and a particle that deep needs no second sum.
  if (-insideValue >= maxRadius) return maxRadius;
  const auto levelSet = [&](float t) {
    glm::vec3 offset;
    return sampledOffsetToMean(particle + t * direction, offset) ? glm::length(offset) - kernelRadius_
                                                                 : kernelRadius_;
  };
  // φ grows by about one per unit along `out` (x̄ moves little): first guess t = −φ(0), then secant steps
  // through the last two points. A lone particle needs none, as φ is then exactly linear.
  float t = -insideValue;
  for (int step = 0; step <= refinements; ++step) {
    const float value = levelSet(t);
    if (value <= 0.0f && t >= maxRadius) return maxRadius;
    // Converged: the secant through two equal points would be 0 / 0 and jump to maxRadius. So would one
    // through two points a rounding error apart, where φ's sampled values bend (their slope then carries
    // only rounding, of either sign).
    if (std::abs(value) <= kConverged * kernelRadius_ || t == inside) return t;
    const float slope = (value - insideValue) / (t - inside);
    const float next = slope > 1e-3f ? t - value / slope : maxRadius;
    inside = t;
    insideValue = value;
    t = std::clamp(next, 0.0f, maxRadius);
  }
  return t;
}

MantaflowSurfaceSearch::MantaflowSurfaceSearch(MantaflowLevelSet levelSet, std::size_t particles)
    : levelSet_(std::move(levelSet)), offsetSearches_(particles), splashSearches_(particles) {}

float MantaflowSurfaceSearch::surfaceDistance(std::size_t index, const glm::vec3& particle, float maxRadius,
                                              int refinements, glm::vec3& out) {
  Search& search = offsetSearches_.at(index);
  if (!search.madeFor(particle, maxRadius, refinements)) {
    glm::vec3 searchedOut;
    const float distance = levelSet_.surfaceDistance(particle, maxRadius, refinements, searchedOut);
    search = {particle, maxRadius, refinements, distance, searchedOut};
  }
  out = search.out;
  return search.distance;
}

float MantaflowSurfaceSearch::inscribedRadius(std::size_t index, const glm::vec3& particle, float maxRadius,
                                              int refinements) {
  Search& search = splashSearches_.at(index);
  if (!search.madeFor(particle, maxRadius, refinements))
    search = {particle, maxRadius, refinements, levelSet_.inscribedRadius(particle, maxRadius, refinements)};
  return search.distance;
}

}  // namespace spindrift
