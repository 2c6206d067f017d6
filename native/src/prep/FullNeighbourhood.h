#pragma once

#include <cstddef>

#include "spindrift/Parameters.h"
#include "spindrift/Particles.h"

namespace spindrift {

/// How many neighbours within R a liquid particle inside the body has: the 90th percentile of the neighbour
/// counts (the particle itself not counted) of a fixed sample of the frame's liquid particles (every k-th, at
/// most about 1,024). It depends on the frame's particles alone, so every view of a frame gets the same. 0
/// for a frame without liquid.
float fullNeighbourCount(const Particles& particles, float neighbourRadius);

/// Yu and Turk's N_epsilon as applied to a frame whose full neighbourhood holds `fullNeighbours`: the smaller
/// of liquid.anisotropy_min_neighbours and liquid.anisotropy_min_neighbour_fraction of the full
/// neighbourhood, but never below the eight neighbours a covariance needs to mean anything (a lattice's
/// corner has seven). A particle with fewer neighbours is drawn as a sphere of k_n r (docs/liquid.md,
/// "Particle preparation").
float appliedMinNeighbours(const LiquidParameters& parameters, float fullNeighbours);

/// What every view of a frame shapes its particles by, from the frame's particles alone (so no view's
/// culling changes it).
struct FrameNeighbourhood {
  float fullNeighbours = 0.0f;  ///< fullNeighbourCount.
  float minNeighbours = 0.0f;   ///< appliedMinNeighbours.
  /// rho_0, the density an interior particle has (docs/liquid.md, "Classify"): the median density of the
  /// interior particles in the grid cells of fullNeighbourCount's sample, each shaped from all its neighbours
  /// as a view shapes it; cells are taken in the sample's order, kRestDensityCellBatch at a time, until
  /// kRestDensityInterior are found. 1 (particles one radius apart) when fewer than
  /// kMinInteriorForRestDensity are; 0 with liquid.layers = merged, which needs no densities.
  float restDensity = 0.0f;
};
FrameNeighbourhood frameNeighbourhood(const Particles& particles, const LiquidParameters& parameters);

constexpr std::size_t kRestDensityInterior = 256;
constexpr std::size_t kRestDensityCellBatch = 32;
constexpr std::size_t kMinInteriorForRestDensity = 64;

}  // namespace spindrift
