#include "prep/NeighbourGrid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "spindrift/Error.h"

namespace spindrift {
namespace {

// Sorts particle indices by key with an LSD radix sort over the bits the keys use (two or three byte passes
// for a typical frame): linear time, and the single-threaded passes cost less than a comparison sort on two
// cores.
std::vector<std::uint32_t> indicesSortedByKey(const std::vector<std::uint64_t>& keys,
                                              std::uint64_t maximumKey) {
  const std::size_t count = keys.size();
  std::vector<std::uint32_t> order(count), scratch(count);
  for (std::size_t i = 0; i < count; ++i)
    order[i] = std::uint32_t(i);
  for (int shift = 0; shift < 64 && (maximumKey >> shift) != 0; shift += 8) {
    std::array<std::size_t, 257> offsets{};
    for (std::uint32_t index : order)
      ++offsets[((keys[index] >> shift) & 0xffu) + 1];
    for (int digit = 0; digit < 256; ++digit)
      offsets[digit + 1] += offsets[digit];
    for (std::uint32_t index : order)
      scratch[offsets[(keys[index] >> shift) & 0xffu]++] = index;
    order.swap(scratch);
  }
  return order;
}

}  // namespace

void ParticleCloud::resize(std::size_t count) {
  x.resize(count);
  y.resize(count);
  z.resize(count);
  radius.resize(count);
  visible.resize(count);
}

NeighbourGrid::NeighbourGrid(ParticleCloud particles, float minimumCellSize) : cellSize_(minimumCellSize) {
  const std::size_t count = particles.size();
  if (count >= std::numeric_limits<std::uint32_t>::max())
    throw Error("too many liquid particles for the neighbour grid: " + std::to_string(count));
  if (!(cellSize_ > 0.0f) || !std::isfinite(cellSize_)) throw Error("neighbour grid: invalid cell size");
  cellBegin_.assign(1, 0);
  if (count == 0) {
    particles_ = std::move(particles);
    return;
  }

  float lower[3] = {particles.x[0], particles.y[0], particles.z[0]};
  float upper[3] = {lower[0], lower[1], lower[2]};
  for (std::size_t i = 0; i < count; ++i) {
    const float position[3] = {particles.x[i], particles.y[i], particles.z[i]};
    for (int axis = 0; axis < 3; ++axis) {
      lower[axis] = std::min(lower[axis], position[axis]);
      upper[axis] = std::max(upper[axis], position[axis]);
    }
  }
  // Coarsen the grid until the keys fit in 62 bits: only a scene thousands of kilometres wide in millimetre
  // cells needs it, and larger cells stay correct (they only hold more candidates).
  std::uint64_t cells[3];
  for (;;) {
    double product = 1.0;
    for (int axis = 0; axis < 3; ++axis) {
      // One cell of margin below and above, and one more in case float rounding puts the highest particle
      // in the next cell.
      cells[axis] = std::uint64_t(std::floor(double(upper[axis] - lower[axis]) / cellSize_)) + 4;
      product *= double(cells[axis]);
    }
    if (product < 0x1p62) break;
    cellSize_ *= 2.0f;
  }
  cellsY_ = cells[1];
  cellsZ_ = cells[2];

  std::vector<std::uint64_t> keys(count);
  const float inverseCellSize = 1.0f / cellSize_;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& block) {
        for (std::size_t i = block.begin(); i != block.end(); ++i) {
          const auto cellIndex = [&](float value, int axis) {
            return std::uint64_t((value - lower[axis]) * inverseCellSize) + 1;
          };
          keys[i] = (cellIndex(particles.x[i], 0) * cellsY_ + cellIndex(particles.y[i], 1)) * cellsZ_ +
                    cellIndex(particles.z[i], 2);
        }
      });
  const std::vector<std::uint32_t> order = indicesSortedByKey(keys, cells[0] * cellsY_ * cellsZ_);

  particles_.resize(count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count),
                    [&](const tbb::blocked_range<std::size_t>& block) {
                      for (std::size_t i = block.begin(); i != block.end(); ++i) {
                        const std::uint32_t source = order[i];
                        particles_.x[i] = particles.x[source];
                        particles_.y[i] = particles.y[source];
                        particles_.z[i] = particles.z[source];
                        particles_.radius[i] = particles.radius[source];
                        particles_.visible[i] = particles.visible[source];
                      }
                    });

  cellBegin_.clear();
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint64_t key = keys[order[i]];
    if (cellKeys_.empty() || cellKeys_.back() != key) {
      cellKeys_.push_back(key);
      cellBegin_.push_back(std::uint32_t(i));
    }
  }
  cellBegin_.push_back(std::uint32_t(count));
}

int NeighbourGrid::neighbourRanges(std::size_t cell, IndexRange ranges[9]) const {
  const std::uint64_t key = cellKeys_[cell];
  const std::uint64_t column = key / cellsZ_;  // ix * cellsY + iy
  const std::uint64_t iz = key % cellsZ_;
  int found = 0;
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      const std::uint64_t neighbourColumn =
          column + std::uint64_t(std::int64_t(dx) * std::int64_t(cellsY_) + dy);
      const std::uint64_t lowKey = neighbourColumn * cellsZ_ + iz - 1;
      const std::uint64_t highKey = lowKey + 2;
      const auto first = std::lower_bound(cellKeys_.begin(), cellKeys_.end(), lowKey);
      const auto last = std::upper_bound(first, cellKeys_.end(), highKey);
      if (first == last) continue;
      ranges[found++] = {cellBegin_[std::size_t(first - cellKeys_.begin())],
                         cellBegin_[std::size_t(last - cellKeys_.begin())]};
    }
  }
  return found;
}

}  // namespace spindrift
