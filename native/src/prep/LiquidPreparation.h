#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "spindrift/Camera.h"
#include "spindrift/Parameters.h"
#include "spindrift/Particles.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// One liquid particle as the impostor passes draw it: the ellipsoid {x : |inverseAxes * (x - centre)| = 1}.
/// A sphere of radius r has inverseAxes = I / r. Laid out for a std430 shader storage buffer (80 bytes).
struct EllipsoidInstance {
  glm::vec4 centreAndBoundingRadius;  ///< World centre; w: radius of a sphere that contains the ellipsoid.
  glm::vec4 inverseAxesRows[3];       ///< Rows of the world-space inverse of the axes matrix; w unused (0).
  /// The window rectangles (x right, y up, inclusive pixels) outside which the ellipsoid cannot hold the
  /// front layer's surface (x, y) and the back layer's (z, w), each as (low | high << 16) per axis:
  /// dropOccludedAggregates finds them (low above high: a layer it is not in); kShownEverywhere where
  /// nothing limits it.
  glm::uvec4 shownRectangles{kShownEverywhere};
  static constexpr std::uint32_t kShownEverywhere = 0xffffffffu;
};
static_assert(sizeof(EllipsoidInstance) == 80, "EllipsoidInstance must match the shaders' std430 layout");

/// One axis of a shown rectangle packed as EllipsoidInstance::shownRectangles holds it.
inline std::uint32_t packPixelRange(int low, int high) {
  return std::uint32_t(low) | std::uint32_t(high) << 16;
}

/// How an ellipsoid list is split between the front and the back depth layer: the first `frontOnly` are drawn
/// into the front layer only, the last `backOnly` into the back layer only, the others into both
/// (dropHiddenInterior orders them so; docs/frame-cost.md).
struct LayerSplit {
  std::size_t frontOnly = 0;
  std::size_t backOnly = 0;
};

/// The liquid particles of one frame, ready to draw: splashes as spheres, the aggregated body as
/// anisotropic ellipsoids (Yu and Turk 2013), as the liquid paper's section 4.1 and 4.2 describe.
struct LiquidPreparation {
  std::vector<EllipsoidInstance> splashes;  ///< Spheres (radius: liquid.mesh_kernel_radius, surface_offset).
  std::vector<EllipsoidInstance> aggregates;  ///< Ellipsoids whose longest axis is at most 1.2 r.
  LayerSplit aggregateLayers;                 ///< Which aggregates each depth layer draws.
  std::size_t culled = 0;                     ///< Outside the view frustum (they still count as neighbours).
  /// In the frustum but hidden wholly by the solids: neighbours only, likewise.
  std::size_t behindSolids = 0;
  std::size_t isotropicInterior = 0;  ///< Aggregates deep inside the body, drawn as spheres without PCA.
  float fullNeighbours = 0.0f;        ///< A particle inside the body has this many neighbours within R.
  float minNeighboursApplied = 0.0f;  ///< N_epsilon as applied: fewer neighbours make a sphere of k_n r.
  /// The frame's rho_0 (frameRestDensity) the splashes were split at; 0 with liquid.layers = merged.
  float restDensity = 0.0f;
  /// The body's typical particle spacing (world units): that of a lattice with fullNeighbours within R of
  /// each particle. 0 without liquid.
  float particleSpacing = 0.0f;
  /// Splashes not drawn because Mantaflow's surface passes below them (liquid.mesh_kernel_radius > 0).
  std::size_t splashesAbsorbed = 0;
  /// For the ray-marched surface (liquid.surface = raymarch; empty otherwise): every liquid candidate, drawn
  /// or only a neighbour, as the drawn surface sizes it. Aggregates: w the offset their ellipsoid is grown by
  /// (world units; liquid.surface_offset r for those not shaped). Splashes: w their sphere's radius. Absorbed
  /// splashes are left out.
  std::vector<glm::vec4> marchedAggregates, marchedSplashes;
  double neighbourMilliseconds = 0.0;
  double anisotropyMilliseconds = 0.0;
  double totalMilliseconds = 0.0;
};

struct FrameLiquidCache;
class SolidDepthTiles;

/// Frustum-culls, finds neighbours, classifies each liquid particle as splash or aggregate by its anisotropic
/// density, and builds the ellipsoids (TBB-parallel). Only particles of kind Liquid are considered.
/// With liquid.layers = merged every visible particle is an aggregate (the earlier two-layer method).
/// The views of one frame pass the same `frameCache` so that what they share (each particle's shape from its
/// neighbours, Mantaflow's surface for liquid.mesh_kernel_radius) is computed once for all of them; the
/// result is the same with or without it.
/// `solids`, when given, is what the background's depth hides: a particle it hides wholly is not drawn (but
/// is a neighbour), unless the surface is ray-marched (liquid.surface = raymarch), whose density sums every
/// particle near the view.
LiquidPreparation prepareLiquid(const Particles& particles, const Camera& camera,
                                const LiquidParameters& parameters, FrameLiquidCache* frameCache = nullptr,
                                const SolidDepthTiles* solids = nullptr);

/// Whether `point` lies inside the drawn aggregated body: inside one of its ellipsoids and, for a Mantaflow
/// liquid, inside the domain's box that clips them. This is how the renderer knows the camera is under water.
bool aggregatesContain(const std::vector<EllipsoidInstance>& aggregates, const glm::vec3& point,
                       const DomainBox* domain);

}  // namespace spindrift
