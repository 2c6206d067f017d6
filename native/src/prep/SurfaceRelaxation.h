#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "spindrift/Parameters.h"
#include "spindrift/Particles.h"

namespace spindrift {

/// What relaxLiquidSurface did to a frame's liquid.
struct SurfaceRelaxationStats {
  std::size_t surfaceParticles = 0;  ///< Liquid particles on the body's surface (density below 90 % of full).
  std::size_t raised = 0;            ///< Of those, moved up onto the surface fitted through their neighbours.
  float spacing = 0.0f;              ///< The particles' spacing it measured (a lattice's step), world units.
  std::string notApplied;            ///< Why it did nothing this frame, if something ruled it out.
  bool kept = false;                 ///< The frame before's result, for the same particles.
  double milliseconds = 0.0;
};

/// Particles sampled on a lattice (or by a solver in layers) leave the body's surface terraced and faceted: a
/// sphere 25 spacings across is a stack of flat discs whose edges are a spacing high, with flat facets where
/// its surface runs along the lattice's planes, and the depth layers' plane fit, a particle or two wide,
/// keeps every terrace and facet wider than itself (docs/liquid.md, "The ball's surface particles"). Each
/// liquid particle on the surface (its kernel density below kSurfaceDensity of full) that lies below the
/// smooth surface through its surface neighbours rises onto it along that surface's normal, by at most
/// kMaxRaiseSpacings of the spacing; none sinks, so a body never shrinks and its outermost particles stay.
/// The smooth surface is an algebraic sphere fitted to the surface neighbours within kFitRadiusSpacings
/// spacings, with the density's normals (Guennebaud and Gross 2007, APSS), weighted towards the outermost
/// particles and those facing the particle's way, so a box's faces stay planes (only near an edge, where the
/// fit bends round it, do particles rise by up to a tenth of a spacing). A body too thin to reach full
/// density inside (a sheet) is a surface only along its rim, and moves within its own plane. Returns the
/// particles with the raised positions; every other particle and attribute is as given.
Particles relaxLiquidSurface(const Particles& particles, const LiquidParameters& parameters,
                             SurfaceRelaxationStats& stats);

/// Whether a frame's liquid is relaxed: liquid.relax_surface, and no Mantaflow surface to stand for
/// (liquid.mesh_kernel_radius 0): a Mantaflow mesh keeps the bumps its particles give it.
bool relaxesSurface(const LiquidParameters& parameters);

/// relaxLiquidSurface's result kept from one frame to the next while the given particles are the same bit for
/// bit and so is liquid.neighbour_radius (liquid.reuse_shapes): a camera moving over a paused frame, as the
/// add-on's viewport redraws it, relaxes its particles once.
class SurfaceRelaxationAcrossFrames {
 public:
  /// The frame's particles as every view draws them: relaxed (relaxesSurface) or `given` itself.
  const Particles& forFrame(const Particles& given, const LiquidParameters& parameters,
                            SurfaceRelaxationStats& stats);

 private:
  Particles given_, relaxed_;
  SurfaceRelaxationStats stats_;
  float neighbourRadius_ = 0.0f;
  bool keyed_ = false;
};

inline constexpr float kKernelRadiusSpacings = 2.5f;  // the density's kernel, H
inline constexpr float kFitRadiusSpacings = 5.0f;     // the sphere's fit, rho
inline constexpr float kMaxRaiseSpacings = 0.75f;
inline constexpr float kSurfaceDensity = 0.9f;  // of full density: below it a particle is on the surface

}  // namespace spindrift
