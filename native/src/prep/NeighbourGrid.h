#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace spindrift {

/// Particles as structure of arrays, the layout the neighbour loops read.
struct ParticleCloud {
  std::vector<float> x, y, z;
  std::vector<float> radius;
  std::vector<std::uint8_t> visible;  ///< 1 where the particle is drawn, 0 where it is only a neighbour.

  std::size_t size() const { return x.size(); }
  void resize(std::size_t count);
};

/// A half-open range of particle indices.
struct IndexRange {
  std::uint32_t begin = 0;
  std::uint32_t end = 0;
};

/// A uniform grid over a particle cloud whose particles are sorted by cell, so that each cell, and each
/// column of three cells along z, is one contiguous range of particles. Every particle within `cellSize` of a
/// particle lies in the 3x3 columns around that particle's cell. Only occupied cells are stored (sorted by
/// key, found by binary search), so a far-away splash costs one cell rather than a grid spanning the scene.
class NeighbourGrid {
 public:
  /// Sorts `particles` by cell. `minimumCellSize` must be at least the largest neighbourhood radius.
  NeighbourGrid(ParticleCloud particles, float minimumCellSize);

  const ParticleCloud& particles() const { return particles_; }
  float cellSize() const { return cellSize_; }
  std::size_t cellCount() const { return cellKeys_.size(); }
  IndexRange cellParticles(std::size_t cell) const { return {cellBegin_[cell], cellBegin_[cell + 1]}; }
  /// The non-empty particle ranges of the 3x3 columns of three cells centred on `cell`; returns how many
  /// (at most 9) were written to `ranges`.
  int neighbourRanges(std::size_t cell, IndexRange ranges[9]) const;

 private:
  ParticleCloud particles_;
  float cellSize_;
  // Cells are numbered key = (ix * cellsY + iy) * cellsZ + iz, with a margin of one empty cell on every side
  // of the bounding box so that the neighbours of an occupied cell never wrap around.
  std::uint64_t cellsY_ = 1;
  std::uint64_t cellsZ_ = 1;
  std::vector<std::uint64_t> cellKeys_;   // Occupied cells, ascending.
  std::vector<std::uint32_t> cellBegin_;  // First particle of each occupied cell; one extra entry at the end.
};

}  // namespace spindrift
