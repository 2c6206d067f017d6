#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "prep/LiquidPreparation.h"
#include "prep/OccludedAggregates.h"
#include "prep/SolidDepthTiles.h"
#include "spindrift/Camera.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// What dropHiddenInterior did to one set of ellipsoids.
struct HiddenInteriorResult {
  std::size_t dropped = 0;  ///< Hidden from both layers: left out.
  LayerSplit split;         ///< Hidden from one layer: drawn into the other only.
  std::string notApplied;   ///< Why nothing was tried, when something ruled it out for this frame.
  double milliseconds = 0.0;
  /// dropHiddenAggregates only: what the view hides besides (dropOccludedAggregates, run after).
  OccludedAggregatesResult occluded;
};

/// Leaves out of each depth layer the ellipsoids that cannot win a pixel of it. The front layer keeps each
/// pixel's nearest entry over all ellipsoids, and an entry point is a camera-facing point of the ellipsoid's
/// surface; if it lies strictly inside another ellipsoid, the ray entered that one earlier. So an ellipsoid
/// whose camera-facing half lies inside the union of the others never wins a front pixel, and likewise the
/// back layer (farthest exit) with the far half: the layers stay bit-identical without it. The ellipsoids
/// are reordered as [front layer only | both | back layer only] (`split` gives the counts), and those hidden
/// from both are left out. Checked conservatively on a voxel grid: a voxel counts as covered when it fits
/// inside the inscribed ball of some ellipsoid, and a half is hidden when every voxel that may touch that
/// half of the surface is covered by another ellipsoid. Rays start at the near plane and end at the far
/// plane, the domain box clips the body and the passes hide a particle whose front lies behind a solid, so
/// nothing is left out when the body reaches the near or far plane, nor any ellipsoid that reaches the
/// domain's walls or may reach behind a solid (`solids`, null where there are none). Nothing is tried when
/// the median ellipsoid's inscribed ball is too small to cover the gaps of a lattice of `particleSpacing`
/// (LiquidPreparation::particleSpacing; 0: not checked), where no voxel between the particles is covered.
HiddenInteriorResult dropHiddenInterior(std::vector<EllipsoidInstance>& ellipsoids, const Camera& camera,
                                        const DomainBox* domain, const SolidDepthTiles* solids = nullptr,
                                        float particleSpacing = 0.0f);

/// Whether at least a tenth of a preparation's aggregates are deep (isotropic: neighbours on every side), so
/// that a view may find much of the body hidden behind its surface.
bool manyDeepAggregates(const LiquidPreparation& liquid);

/// dropHiddenInterior on a preparation's aggregates (where manyDeepAggregates), then
/// dropOccludedAggregates, recording the split in `liquid.aggregateLayers`; `solids` are the frame's, or
/// null; `workspace` is lent to dropOccludedAggregates.
HiddenInteriorResult dropHiddenAggregates(LiquidPreparation& liquid, const Camera& camera,
                                          const DomainBox* domain, const SolidDepthTiles* solids = nullptr,
                                          OcclusionWorkspace* workspace = nullptr);

}  // namespace spindrift
