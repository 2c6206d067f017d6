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

/// A bound of a linear map's largest stretch, its Frobenius norm: a ball of radius r maps into one of radius
/// r times this.
inline float stretchBound(const glm::mat3& linear) {
  return std::sqrt(glm::dot(linear[0], linear[0]) + glm::dot(linear[1], linear[1]) +
                   glm::dot(linear[2], linear[2]));
}

/// The radius of a ball about the centre that lies inside the ellipsoid: its shortest semi-axis, or less.
inline float inscribedRadius(const EllipsoidInstance& ellipsoid) {
  return 1.0f / largestSingularValue(ellipsoid);
}

}  // namespace spindrift
