#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>

#include "prep/FoamPreparation.h"
#include "spindrift/Camera.h"

namespace spindrift {

/// Where foam can be seen, per screen tile (FoamVisibilityPass): the eye depth beyond which a foam fragment
/// shows in no foam layer, because the solids hide it or it lies deeper under the liquid than
/// foam.attenuation_distance, where f_att is 0.
struct FoamVisibilityTiles {
  int tileSize = 8;  ///< Pixels per tile side.
  int columns = 0;
  int rows = 0;
  /// Per tile, row 0 at the bottom (as the window): x, behind the solids; y, behind the solids or under the
  /// liquid. The largest over the tile's pixels.
  std::vector<glm::vec2> hiddenBeyond;
};

/// The foam particles some fragment of which may show, in their order, and those left out.
struct VisibleFoam {
  std::vector<FoamInstance> instances;
  std::size_t behindSolids = 0;  ///< The solids hide the whole sprite.
  std::size_t underLiquid = 0;   ///< Deeper under the liquid than attenuation_distance (or behind solids).
};

/// Leaves out every particle whose sphere lies wholly beyond the tiles' depth over the tiles its sprite (a
/// camera-facing square of its radius) covers. Such a particle adds no thickness and is no pixel's nearest
/// foam where any foam shows, so every foam layer is the same without it (docs/foam.md).
VisibleFoam cullHiddenFoam(const std::vector<FoamInstance>& instances, const Camera& camera,
                           const FoamVisibilityTiles& tiles);

}  // namespace spindrift
