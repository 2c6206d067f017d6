#pragma once

#include <cstdint>
#include <vector>

#include "prep/NeighbourGrid.h"

namespace spindrift {

/// The particles of some candidate ranges that lie within a neighbourhood of radius R of one particle (the
/// particle itself included), as offsets from it. A particle's 3 x 3 columns of three cells hold six times
/// the ball's volume, and 3.9 candidates for each neighbour on the dam break (303 for 78; 4.5 on the
/// benchmark's bigger bake): the anisotropy's sums run over the neighbours alone (docs/frame-cost.md). A
/// candidate is kept where q = (x_j - x_i) / R has |q|^2 < 1, computed as the sums compute it, so that the
/// same ones are kept whichever way the compaction runs.
class NeighbourOffsets {
 public:
  /// How the kept indices are compacted: AVX-512's compress where the CPU has it, else a branch-free scalar
  /// loop; both keep the same candidates in the same order.
  enum class Compaction { Fastest, Portable };

  /// Replaces the offsets with those of the particles of `ranges` within 1 / inverseRadius of `particle`.
  void gather(const ParticleCloud& cloud, std::uint32_t particle, float inverseRadius,
              const IndexRange* ranges, int rangeCount, Compaction compaction = Compaction::Fastest);

  int count() const { return count_; }
  /// x_j - x_i, world units, for j < count(); the particle's own offset (0, 0, 0) among them.
  const float* x() const { return x_.data(); }
  const float* y() const { return y_.data(); }
  const float* z() const { return z_.data(); }
  /// The cloud indices kept, in candidate order.
  const std::uint32_t* indices() const { return kept_.data(); }

 private:
  std::vector<float> x_, y_, z_;
  std::vector<float> squaredDistances_;
  std::vector<std::uint32_t> kept_;
  int count_ = 0;
};

}  // namespace spindrift
