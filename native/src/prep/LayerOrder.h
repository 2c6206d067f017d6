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

}  // namespace spindrift
