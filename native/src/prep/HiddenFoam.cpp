#include "prep/HiddenFoam.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

namespace spindrift {
namespace {

// Tiles a sprite may cover and still be tested: a larger one is near the camera, rare, and simply drawn.
constexpr int kMaximumTestedTiles = 16;
// The sphere's nearest depth must lie this fraction beyond the tiles' depth: the shaders compute depths in
// another order, and a fragment exactly attenuation_distance under the liquid is not always faded to zero.
constexpr float kMargin = 1e-4f;

enum class Hidden : std::uint8_t { No, BehindSolids, UnderLiquid };

}  // namespace

VisibleFoam cullHiddenFoam(const std::vector<FoamInstance>& instances, const Camera& camera,
                           const FoamVisibilityTiles& tiles) {
  VisibleFoam result;
  result.instances.reserve(instances.size());
  const glm::mat4 cameraFromWorld = camera.cameraFromWorld();
  const glm::mat4 clipFromCamera = camera.clipFromCamera();
  // The sprite's corners centre -+ (r, r, 0) in camera space move its clip position by -+ r (column x +
  // column y) of clipFromCamera.
  const glm::vec4 cornerStep = clipFromCamera[0] + clipFromCamera[1];
  const glm::vec2 size(float(camera.width), float(camera.height));
  // Window position of a clip-space point, as shaders/lib/frame.glsl's fragCoordFromCamera.
  auto windowOf = [&](const glm::vec4& clip) { return (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * size; };
  auto tileOf = [&](float coordinate, int count) {
    const float tile = std::floor(coordinate / float(tiles.tileSize));
    return int(std::clamp(tile, 0.0f, float(count - 1)));
  };
  auto hiddenBy = [&](const FoamInstance& instance) {
    const glm::vec3 centre =
        glm::vec3(cameraFromWorld * glm::vec4(glm::vec3(instance.centreAndRadius), 1.0f));
    const float radius = instance.centreAndRadius.w;
    const float nearest = -centre.z - radius;
    if (!(nearest > camera.nearClip)) return Hidden::No;
    const glm::vec4 clip = clipFromCamera * glm::vec4(centre, 1.0f);
    const glm::vec2 low = windowOf(clip - radius * cornerStep), high = windowOf(clip + radius * cornerStep);
    const int firstColumn = tileOf(low.x, tiles.columns), lastColumn = tileOf(high.x, tiles.columns);
    const int firstRow = tileOf(low.y, tiles.rows), lastRow = tileOf(high.y, tiles.rows);
    if ((lastColumn - firstColumn + 1) * (lastRow - firstRow + 1) > kMaximumTestedTiles) return Hidden::No;
    glm::vec2 beyond(0.0f);
    for (int row = firstRow; row <= lastRow; ++row)
      for (int column = firstColumn; column <= lastColumn; ++column)
        for (int axis = 0; axis < 2; ++axis) {
          // A NaN tile hides nothing.
          const float tile = tiles.hiddenBeyond[std::size_t(row) * tiles.columns + column][axis];
          beyond[axis] =
              std::isnan(tile) ? std::numeric_limits<float>::infinity() : std::max(beyond[axis], tile);
        }
    if (nearest > beyond.x * (1.0f + kMargin)) return Hidden::BehindSolids;
    return nearest > beyond.y * (1.0f + kMargin) ? Hidden::UnderLiquid : Hidden::No;
  };
  // Tested in parallel, kept in order: the sprite passes draw the survivors as they would have drawn all.
  std::vector<Hidden> hidden(instances.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, instances.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        hidden[i] = hiddenBy(instances[i]);
                    });
  for (std::size_t i = 0; i < instances.size(); ++i) {
    switch (hidden[i]) {
      case Hidden::No:
        result.instances.push_back(instances[i]);
        break;
      case Hidden::BehindSolids:
        ++result.behindSolids;
        break;
      case Hidden::UnderLiquid:
        ++result.underLiquid;
        break;
    }
  }
  return result;
}

}  // namespace spindrift
