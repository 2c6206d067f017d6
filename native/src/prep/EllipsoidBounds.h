#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "prep/LiquidPreparation.h"

namespace spindrift {

/// The largest singular value of the matrix whose rows are the ellipsoid's inverse axes, bounded from above
/// by Gershgorin's theorem on M M^T: exact for orthogonal rows (an ellipsoid's), and never smaller than the
/// true value, which keeps the bounds below conservative.
inline float largestSingularValue(const EllipsoidInstance& ellipsoid) {
  float largest = 0.0f;
  for (int i = 0; i < 3; ++i) {
    float rowSum = 0.0f;
    for (int j = 0; j < 3; ++j)
      rowSum += std::abs(
          glm::dot(glm::vec3(ellipsoid.inverseAxesRows[i]), glm::vec3(ellipsoid.inverseAxesRows[j])));
    largest = std::max(largest, rowSum);
  }
  return std::sqrt(largest);
}

/// The radius of a ball about the centre that lies inside the ellipsoid: its shortest semi-axis, or less.
inline float inscribedRadius(const EllipsoidInstance& ellipsoid) {
  return 1.0f / largestSingularValue(ellipsoid);
}

}  // namespace spindrift
