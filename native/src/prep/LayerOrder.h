#pragma once

#include <cstddef>
#include <vector>

#include "prep/LiquidPreparation.h"

namespace spindrift {

/// Orders ellipsoids as the impostor pass draws them, [front layer only | both | back layer only], each group
/// in its previous order, and leaves out those in neither layer. `inFront` and `inBack` say, per ellipsoid,
/// which layers it is drawn into. Returns the split of the new order.
LayerSplit orderByLayers(std::vector<EllipsoidInstance>& ellipsoids, const std::vector<char>& inFront,
                         const std::vector<char>& inBack);

/// Leaves only the back layer's ellipsoids, in their order, the front layer drawing none: for a view whose
/// front layer no pass reads (the camera under water). Returns how many were left out (front layer only).
std::size_t keepBackLayerOnly(std::vector<EllipsoidInstance>& ellipsoids, LayerSplit& split);

}  // namespace spindrift
