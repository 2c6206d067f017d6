#include "prep/MantaflowSurface.h"

#include <algorithm>
#include <cmath>
#include <cstring>
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

// A node of the sampled lattice lies at the same place in its cell as every other (lattice and cells share
// their spacing), so the cells that may hold a centroid within 2 r_m = 4 cells of it are those within 4 cells
// of its own along each axis: a fixed stencil of 9 x 9 columns of 9 cells each, less the four corner columns
// (their cells lie at least 3 cells off along both axes, beyond 4), each column summed as one 16-lane vector.
constexpr int kStencilReach = 4;
constexpr int kRunLanes = 16;
using Float16 = float __attribute__((vector_size(4 * kRunLanes)));

// The cells as the stencil's sums read them (MantaflowLevelSet's members).
struct CellColumns {
  const float *x, *y, *z, *count;
  const std::int32_t *occupiedLow, *occupiedHigh;
  int counts[3];
};

// runMasks[n]: 1 in the first n + 1 lanes, 0 past them.
const struct RunMasks {
  Float16 masks[kRunLanes];
  RunMasks() {
    for (int n = 0; n < kRunLanes; ++n)
      for (int lane = 0; lane < kRunLanes; ++lane)
        masks[n][lane] = lane <= n ? 1.0f : 0.0f;
  }
} runMasks;

// A run of cells from `first` (into a reference: a 64-byte vector returned by value would take AVX-512's
// ABI).
void loadRun(const float* first, Float16& run) {
  std::memcpy(&run, first, sizeof run);
}

// Σ count·max(0, 1 − d²/support²)·(c − at) and Σ count·max(0, 1 − d²/support²) over the cells of the stencil
// about `cell` (`at`'s own), c each cell's centroid: `sums` = (x, y, z, weight). A cell past the support adds
// exactly 0, so these are offsetToMean's sums but for their order: each lane sums its cells in the columns'
// order and the lanes are added in order, the same in both clones (the file has no fused multiply-adds).
__attribute__((target_clones("avx512f", "default"))) void sumOverStencil(const CellColumns& cells,
                                                                         const glm::ivec3& cell,
                                                                         const glm::vec3& at,
                                                                         float inverseSupportSquared,
                                                                         float sums[4]) {
  const Float16 zero = {};
  Float16 sumX = zero, sumY = zero, sumZ = zero, sumWeight = zero;
  for (int dx = -kStencilReach; dx <= kStencilReach; ++dx) {
    const int ix = cell.x + dx;
    if (ix < 0 || ix >= cells.counts[0]) continue;
    for (int dy = -kStencilReach; dy <= kStencilReach; ++dy) {
      const int iy = cell.y + dy;
      if (iy < 0 || iy >= cells.counts[1]) continue;
      if (std::abs(dx) == kStencilReach && std::abs(dy) == kStencilReach) continue;
      const std::size_t column = std::size_t(ix) * std::size_t(cells.counts[1]) + std::size_t(iy);
      const int z0 = std::max(cell.z - kStencilReach, cells.occupiedLow[column]);
      const int z1 = std::min(cell.z + kStencilReach, cells.occupiedHigh[column]);
      if (z1 < z0) continue;
      const std::size_t first = column * std::size_t(cells.counts[2]) + std::size_t(z0);
      Float16 dX, dY, dZ, count;
      loadRun(cells.x + first, dX);
      loadRun(cells.y + first, dY);
      loadRun(cells.z + first, dZ);
      loadRun(cells.count + first, count);
      dX -= at.x;
      dY -= at.y;
      dZ -= at.z;
      const Float16 falloff = 1.0f - (dX * dX + dY * dY + dZ * dZ) * inverseSupportSquared;
      // max(0, falloff) and 0 past the run as factors, which stay vector operations (a select on two masks
      // took GCC to a branch per lane).
      const Float16 weight = count * (falloff > zero ? falloff : zero) * runMasks.masks[z1 - z0];
      sumX += weight * dX;
      sumY += weight * dY;
      sumZ += weight * dZ;
      sumWeight += weight;
    }
  }
  const Float16* lanes[4] = {&sumX, &sumY, &sumZ, &sumWeight};
  for (int k = 0; k < 4; ++k) {
    sums[k] = 0.0f;
    for (int lane = 0; lane < kRunLanes; ++lane)
      sums[k] += (*lanes[k])[lane];
  }
}

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
  const std::size_t cells = columns * std::size_t(cellCounts_[2]);
  // Padded so that a stencil's run loads 16 lanes from any cell.
  for (std::vector<float>* component : {&cellX_, &cellY_, &cellZ_, &cellCount_})
    component->assign(cells + kRunLanes, 0.0f);
  occupiedLow_.assign(columns, cellCounts_[2]);
  occupiedHigh_.assign(columns, -1);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    int index[3];
    const float position[3] = {cloud.x[i], cloud.y[i], cloud.z[i]};
    for (int axis = 0; axis < 3; ++axis)
      index[axis] = std::clamp(int((position[axis] - origin_[axis]) / cellSize_), 0, cellCounts_[axis] - 1);
    const std::size_t column = std::size_t(index[0]) * std::size_t(cellCounts_[1]) + std::size_t(index[1]);
    const std::size_t cell = column * std::size_t(cellCounts_[2]) + std::size_t(index[2]);
    cellX_[cell] += position[0];
    cellY_[cell] += position[1];
    cellZ_[cell] += position[2];
    cellCount_[cell] += 1.0f;
    occupiedLow_[column] = std::min(occupiedLow_[column], index[2]);
    occupiedHigh_[column] = std::max(occupiedHigh_[column], index[2]);
  }
  for (std::size_t cell = 0; cell < cells; ++cell) {
    const float count = cellCount_[cell];
    if (count == 0.0f) continue;
    cellX_[cell] /= count;
    cellY_[cell] /= count;
    cellZ_[cell] /= count;
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
  const glm::vec3 at = nodeSpacing_ * glm::vec3(nodeLow_ + node);
  const CellColumns cells{cellX_.data(),
                          cellY_.data(),
                          cellZ_.data(),
                          cellCount_.data(),
                          occupiedLow_.data(),
                          occupiedHigh_.data(),
                          {cellCounts_[0], cellCounts_[1], cellCounts_[2]}};
  // The node's cell, unclamped: a node up to 2 r_m outside the cloud's box lies in no cell.
  const glm::ivec3 cell(glm::floor((at - origin_) / cellSize_));
  const float support = 2.0f * kernelRadius_;
  float sums[4];
  sumOverStencil(cells, cell, at, 1.0f / (support * support), sums);
  const bool near = sums[3] > 0.0f;
  const glm::vec3 offset = near ? glm::vec3(sums[0], sums[1], sums[2]) / sums[3] : glm::vec3(0.0f);
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
  // Summed in the order of the cells.
  float sums[4] = {0.0f, 0.0f, 0.0f, 0.0f};
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
      const std::size_t run = column * std::size_t(cellCounts_[2]);
      for (int iz = z0; iz <= z1; ++iz) {
        const std::size_t cell = run + std::size_t(iz);
        const float dx = cellX_[cell] - at.x, dy = cellY_[cell] - at.y, dz = cellZ_[cell] - at.z;
        const float falloff = 1.0f - (dx * dx + dy * dy + dz * dz) * inverseSupportSquared;
        const float weight = cellCount_[cell] * (falloff > 0.0f ? falloff : 0.0f);
        sums[0] += weight * dx;
        sums[1] += weight * dy;
        sums[2] += weight * dz;
        sums[3] += weight;
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
