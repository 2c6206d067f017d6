#pragma once

#include <cstddef>

#include "prep/Anisotropy.h"
#include "prep/LiquidPreparation.h"
#include "prep/MantaflowSurface.h"
#include "prep/NeighbourGrid.h"
#include "prep/SolidDepthTiles.h"

// The stages of prepareLiquid, exposed for the benchmark and the tests: select → grid → shape → classify.
namespace spindrift {

/// The liquid particles that are drawn (visible) or that can be a drawn particle's neighbour (within the
/// neighbourhood radius of the frustum), and the grid cell size their neighbourhoods need.
struct LiquidCandidates {
  ParticleCloud cloud;
  std::size_t culled = 0;        ///< Outside the frustum: not drawn.
  std::size_t behindSolids = 0;  ///< In the frustum, but the solids hide them wholly: not drawn.
  std::size_t eligible = 0;      ///< Liquid particles with a finite position and a positive finite radius.
  float cellSize = 1.0f;
};

/// The liquid particles this view draws (their drawn reach meets the frustum and, given `solids`, the
/// background's solids do not hide it wholly) and their neighbours.
LiquidCandidates selectLiquidCandidates(const Particles& particles, const Camera& camera,
                                        const LiquidParameters& parameters,
                                        const SolidDepthTiles* solids = nullptr);

/// Splits the shaped particles into splashes (density below liquid.splash_density_threshold times
/// `restDensity`, the frame's rho_0 (frameRestDensity); spheres of radius r at the particle) and aggregates,
/// filling those fields of `preparation`.
/// With `meshSurface` (Mantaflow's surface, or null), each splash is a sphere as large as that surface
/// reaches around it, and splashes it passes below are not drawn (LiquidPreparation::splashesAbsorbed); the
/// searches are remembered in it.
void classifyAndPack(const NeighbourGrid& grid, const ParticleShapes& shapes, float restDensity,
                     const LiquidParameters& parameters, MantaflowSurfaceSearch* meshSurface,
                     LiquidPreparation& preparation);

}  // namespace spindrift
