#include "prep/LayerOrder.h"

#include <cstddef>

namespace spindrift {

LayerSplit orderByLayers(std::vector<EllipsoidInstance>& ellipsoids, const std::vector<char>& inFront,
                         const std::vector<char>& inBack) {
  std::vector<EllipsoidInstance> frontOnly, both, backOnly;
  for (std::size_t i = 0; i < ellipsoids.size(); ++i) {
    if (!inFront[i] && !inBack[i]) continue;
    (inFront[i] && inBack[i] ? both : inFront[i] ? frontOnly : backOnly).push_back(ellipsoids[i]);
  }
  const LayerSplit split{frontOnly.size(), backOnly.size()};
  ellipsoids = std::move(frontOnly);
  ellipsoids.insert(ellipsoids.end(), both.begin(), both.end());
  ellipsoids.insert(ellipsoids.end(), backOnly.begin(), backOnly.end());
  return split;
}

std::size_t keepBackLayerOnly(std::vector<EllipsoidInstance>& ellipsoids, LayerSplit& split) {
  const std::size_t leftOut = split.frontOnly;
  ellipsoids.erase(ellipsoids.begin(), ellipsoids.begin() + std::ptrdiff_t(leftOut));
  split = LayerSplit{0, ellipsoids.size()};
  return leftOut;
}

}  // namespace spindrift
