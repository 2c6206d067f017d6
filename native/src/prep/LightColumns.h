#pragma once

#include <cstddef>
#include <vector>

#include "prep/LiquidPreparation.h"
#include "spindrift/Camera.h"

namespace spindrift {

/// Thins a light's view (light.column_particles): in each column of `columnSide` × `columnSide` texels of
/// `view`, the front layer keeps the `perColumn` ellipsoids whose centres lie nearest the view and the back
/// layer the `perColumn` farthest (ties in the list's order); the others are left out. A column's nearest
/// centres hold its front surface, as its farthest hold its back, wherever the body is a few particles deep
/// and each particle spans several texels: a Mantaflow sheet in a sun's view of 128 texels holds 3.4
/// particles a column, each about 28 texels, an overdraw near 100 a layer. A column narrower than the
/// particles' spacing (columnSideFor) holds about one particle of each layer of a deeper body, so its ends
/// are that body's top and bottom layers. An ellipsoid whose centre does not project into the view is kept in
/// both layers. `ellipsoids` is reordered as [front only | both | back only] (`split`); returns how many were
/// left out.
std::size_t keepColumnEnds(std::vector<EllipsoidInstance>& ellipsoids, LayerSplit& split, const Camera& view,
                           int perColumn, int columnSide = 1);

/// The side in texels of the columns keepColumnEnds thins a lamp's view by: as many texels as fit in
/// kColumnSpacingFraction of the particles' spacing (LiquidPreparation::particleSpacing), at least one. The
/// light benchmark's lattices (a spacing of 2.7 to 3.0 texels) take 2; a Mantaflow liquid, whose spacing is
/// under a texel (its views resolve the kernel radius), takes 1.
int columnSideFor(float particleSpacing, float texelSize);

/// A column this fraction of the particles' spacing wide never holds two neighbours of one layer side by
/// side. Columns of 3 texels on a lattice 3.0 apart (a fraction of 1) moved the light benchmark's block from
/// 0.0614 to 0.0654 (docs/frame-cost.md, session 58).
inline constexpr float kColumnSpacingFraction = 0.75f;

}  // namespace spindrift
