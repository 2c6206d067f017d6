#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "prep/NeighbourGrid.h"

namespace spindrift {

/// How far Mantaflow's mesh reaches out from liquid particle `i` of `grid`, in world units, by its averaged
/// (Zhu–Bridson) particle level set φ(x) = |x − x̄(x)| − r_m with weights max(0, 1 − d²/(2 r_m)²)
/// (docs/mantaflow-caches.md), `kernelRadius` being r_m: 0 when the particle itself lies outside that surface
/// (its neighbours pull x̄ more than r_m away: Mantaflow draws no bump for it, the body's surface passes near
/// it), else the distance to φ = 0 from the particle along `out`, the direction away from x̄(particle), at
/// most `maxRadius`. A lone particle gets r_m. The zero is found by secant steps (`refinements` after the
/// first guess; each costs one sum over the particles within 2 r_m). The concavity correction (c ≤ 1) and the
/// mesh smoothing are left out: both only matter where the surface is concave or curved within a few cells.
/// `ranges` is scratch space.
float mantaflowSurfaceDistance(const NeighbourGrid& grid, std::size_t i, float kernelRadius, float maxRadius,
                               int refinements, std::vector<IndexRange>& ranges, glm::vec3& out);

}  // namespace spindrift
