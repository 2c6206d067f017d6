#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "prep/LiquidPreparation.h"

// A double-precision CPU ray cast of one ellipsoid instance, the reference the impostor tests compare with.
namespace ellipsoid_test {

struct Chord {
  double entry = 0.0;  // in units of the direction's length
  double exit = 0.0;
  double miss = 0.0;  // 1 - |closest point|^2 in the unit sphere's space: > 0 where the ray enters
};

// Solving around the ray's closest approach keeps the discriminant accurate far from the ellipsoid. The chord
// is meaningful only where miss >= 0.
inline Chord castRay(const spindrift::EllipsoidInstance& ellipsoid, const glm::dvec3& origin,
                     const glm::dvec3& direction) {
  const glm::dmat3 inverseAxes = glm::transpose(glm::dmat3(glm::dvec3(ellipsoid.inverseAxesRows[0]),
                                                           glm::dvec3(ellipsoid.inverseAxesRows[1]),
                                                           glm::dvec3(ellipsoid.inverseAxesRows[2])));
  const glm::dvec3 o = inverseAxes * (origin - glm::dvec3(ellipsoid.centreAndBoundingRadius));
  const glm::dvec3 d = inverseAxes * direction;
  const double a = glm::dot(d, d), closest = -glm::dot(o, d) / a;
  const glm::dvec3 closestPoint = o + closest * d;
  Chord chord;
  chord.miss = 1.0 - glm::dot(closestPoint, closestPoint);
  if (chord.miss < 0.0) return chord;
  const double halfChord = std::sqrt(chord.miss / a);
  chord.entry = closest - halfChord;
  chord.exit = closest + halfChord;
  return chord;
}

// Nearest entry and farthest exit of a ray over a set of ellipsoids, in units of the direction's length
// (1e10 and -1e10 where it meets none).
inline std::pair<double, double> nearestEntryAndFarthestExit(
    const std::vector<spindrift::EllipsoidInstance>& ellipsoids, const glm::dvec3& origin,
    const glm::dvec3& direction) {
  double nearest = 1e10, farthest = -1e10;
  for (const spindrift::EllipsoidInstance& ellipsoid : ellipsoids) {
    const Chord chord = castRay(ellipsoid, origin, direction);
    if (chord.miss < 0.0) continue;
    nearest = std::min(nearest, chord.entry);
    farthest = std::max(farthest, chord.exit);
  }
  return {nearest, farthest};
}

// Whether two instances are the same ellipsoid (centre, bound and axes), whatever shown rectangles the
// occlusion test gave either.
inline bool sameShape(const spindrift::EllipsoidInstance& a, const spindrift::EllipsoidInstance& b) {
  return std::memcmp(&a, &b, offsetof(spindrift::EllipsoidInstance, shownRectangles)) == 0;
}

// Whether the impostor pass draws the ellipsoid's fragment at a window pixel (x right, y up) in the front or
// the back layer: inside that layer's shown rectangle, or anywhere where it has none.
inline bool shownAt(const spindrift::EllipsoidInstance& ellipsoid, bool back, int x, int y) {
  const std::uint32_t columns = back ? ellipsoid.shownRectangles.z : ellipsoid.shownRectangles.x;
  const std::uint32_t rows = back ? ellipsoid.shownRectangles.w : ellipsoid.shownRectangles.y;
  if (columns == spindrift::EllipsoidInstance::kShownEverywhere) return true;
  return int(columns & 0xffffu) <= x && x <= int(columns >> 16) && int(rows & 0xffffu) <= y &&
         y <= int(rows >> 16);
}

// The ellipsoids of a layer's list that the impostor pass draws at a window pixel (x right, y up).
inline std::vector<spindrift::EllipsoidInstance> shownAtPixel(
    const std::vector<spindrift::EllipsoidInstance>& layer, bool back, int x, int y) {
  std::vector<spindrift::EllipsoidInstance> shown;
  for (const spindrift::EllipsoidInstance& ellipsoid : layer)
    if (shownAt(ellipsoid, back, x, y)) shown.push_back(ellipsoid);
  return shown;
}

}  // namespace ellipsoid_test
