#pragma once

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

}  // namespace spindrift
