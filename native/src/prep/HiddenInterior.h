#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "prep/LiquidPreparation.h"
#include "prep/SolidDepthTiles.h"
#include "spindrift/Camera.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// What dropHiddenInterior did to one set of ellipsoids.
struct HiddenInteriorResult {
  std::size_t dropped = 0;
  std::string notApplied;  ///< Why nothing was tried, when something ruled it out for this frame.
  double milliseconds = 0.0;
};

/// Removes the ellipsoids that lie inside the interior of the union of the others. A depth layer keeps the
/// nearest entry (front) or farthest exit (back) over all ellipsoids; a point of such an ellipsoid is never
/// on the union's boundary, so the ellipsoid never wins a pixel and the layers stay bit-identical without it
/// (the union of those kept may have cavities, but no ray reaches them first). It is checked conservatively
/// on a voxel grid: a voxel counts as covered when it fits inside the inscribed ball of some ellipsoid, and
/// an ellipsoid is dropped when every voxel that may touch it is covered by another one. Rays start at the
/// near plane and end at the far plane, the domain box clips the body and the passes hide a particle whose
/// front lies behind a solid, so nothing is dropped when the body reaches the near or far plane, nor any
/// ellipsoid that reaches the domain's walls or may reach behind a solid (`solids`, null where there are
/// none).
HiddenInteriorResult dropHiddenInterior(std::vector<EllipsoidInstance>& ellipsoids, const Camera& camera,
                                        const DomainBox* domain, const SolidDepthTiles* solids = nullptr);

/// dropHiddenInterior on a preparation's aggregates, unless few of them are deep inside the body. `solids`,
/// when given, makes the frame's solids; it is called only when the step is tried (its cost, a pass over the
/// background's depth, is not paid on frames that skip the step).
HiddenInteriorResult dropHiddenAggregates(LiquidPreparation& liquid, const Camera& camera,
                                          const DomainBox* domain,
                                          const std::function<SolidDepthTiles()>& solids = {});

}  // namespace spindrift
