#include "prep/LightColumns.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "prep/LayerOrder.h"

namespace spindrift {

std::size_t keepColumnEnds(std::vector<EllipsoidInstance>& ellipsoids, LayerSplit& split, const Camera& view,
                           int perColumn, int columnSide) {
  const std::size_t count = ellipsoids.size();
  if (perColumn <= 0 || count == 0 || view.width <= 0 || view.height <= 0) return 0;
  // Each centre's column and depth along the view; kOutside where it projects nowhere on the view.
  constexpr std::uint32_t kOutside = ~std::uint32_t(0);
  const std::uint32_t side = std::uint32_t(std::max(columnSide, 1));
  const std::uint32_t across = (std::uint32_t(view.width) + side - 1) / side;
  const std::uint32_t columns = across * ((std::uint32_t(view.height) + side - 1) / side);
  const glm::mat4 cameraFromWorld = view.cameraFromWorld();
  std::vector<std::uint32_t> columnOf(count, kOutside);
  std::vector<float> depthOf(count, 0.0f);
  for (std::size_t i = 0; i < count; ++i) {
    const glm::vec3 centre(cameraFromWorld *
                           glm::vec4(glm::vec3(ellipsoids[i].centreAndBoundingRadius), 1.0f));
    const glm::vec3 pixel = view.pixelAndDepthFromCamera(centre);
    if (!(pixel.z > 0.0f) || !(pixel.x >= 0.0f && pixel.x < float(view.width)) ||
        !(pixel.y >= 0.0f && pixel.y < float(view.height)))
      continue;
    columnOf[i] = std::uint32_t(pixel.y) / side * across + std::uint32_t(pixel.x) / side;
    depthOf[i] = pixel.z;
  }
  // The ellipsoids by column (a counting sort, each column in the list's order), then each column's ends.
  std::vector<std::uint32_t> columnStart(std::size_t(columns) + 1, 0);
  for (std::size_t i = 0; i < count; ++i)
    if (columnOf[i] != kOutside) ++columnStart[columnOf[i] + 1];
  for (std::uint32_t c = 0; c < columns; ++c)
    columnStart[c + 1] += columnStart[c];
  std::vector<std::uint32_t> byColumn(columnStart.back());
  std::vector<std::uint32_t> next(columnStart.begin(), columnStart.end() - 1);
  for (std::size_t i = 0; i < count; ++i)
    if (columnOf[i] != kOutside) byColumn[next[columnOf[i]]++] = std::uint32_t(i);

  std::vector<char> inFront(count), inBack(count);
  for (std::size_t i = 0; i < count; ++i)
    inFront[i] = inBack[i] = columnOf[i] == kOutside;
  const std::size_t keep = std::size_t(perColumn);
  const auto nearer = [&](std::uint32_t a, std::uint32_t b) {
    return depthOf[a] < depthOf[b] || (depthOf[a] == depthOf[b] && a < b);
  };
  for (std::uint32_t c = 0; c < columns; ++c) {
    const auto first = byColumn.begin() + columnStart[c], last = byColumn.begin() + columnStart[c + 1];
    const std::size_t size = std::size_t(last - first);
    if (size <= keep) {
      for (auto it = first; it != last; ++it)
        inFront[*it] = inBack[*it] = 1;
      continue;
    }
    std::sort(first, last, nearer);
    for (std::size_t k = 0; k < keep; ++k) {
      inFront[*(first + std::ptrdiff_t(k))] = 1;
      inBack[*(last - 1 - std::ptrdiff_t(k))] = 1;
    }
  }
  split = orderByLayers(ellipsoids, inFront, inBack);
  return count - ellipsoids.size();
}

int columnSideFor(float particleSpacing, float texelSize) {
  const float side = std::floor(kColumnSpacingFraction * particleSpacing / texelSize);
  // Below one, or not a number (no spacing, no texel): a texel.
  return side >= 1.0f ? int(std::min(side, 64.0f)) : 1;
}

}  // namespace spindrift
