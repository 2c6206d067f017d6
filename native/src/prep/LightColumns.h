#pragma once

#include <cstddef>
#include <vector>

#include "prep/LiquidPreparation.h"
#include "spindrift/Camera.h"

namespace spindrift {

/// Thins a light's view of a body few particles deep (light.column_particles): in each texel column of
/// `view`, the front layer keeps the `perColumn` ellipsoids whose centres lie nearest the view and the back
/// layer the `perColumn` farthest (ties in the list's order); the others are left out. A column's nearest
/// centres hold its front surface, as its farthest hold its back, wherever the body is a few particles deep
/// and each particle spans several texels: a Mantaflow sheet in a sun's view of 128 texels holds 3.4
/// particles a column, each about 28 texels, an overdraw near 100 a layer. An ellipsoid whose centre does not
/// project into the view is kept in both layers. `ellipsoids` is reordered as [front only | both | back
/// only] (`split`); returns how many were left out.
std::size_t keepColumnEnds(std::vector<EllipsoidInstance>& ellipsoids, LayerSplit& split, const Camera& view,
                           int perColumn);

}  // namespace spindrift
