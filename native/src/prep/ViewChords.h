#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "prep/LiquidPreparation.h"
#include "spindrift/Camera.h"
#include "spindrift/Scene.h"

// The geometry of the occlusion test (prep/OccludedAggregates.cpp): where the rays through a view's pixel
// centres enter and leave an ellipsoid and a domain box, in double precision.
namespace spindrift::view_chords {

// An ellipsoid in camera space, {x : |M (x - c)| <= 1}: the rows of M and M c.
struct CameraEllipsoid {
  glm::dvec3 rows[3];
  glm::dvec3 scaledCentre{0.0};
};

/// The ellipsoid in camera space: `cameraFromWorld` is the view's rotation, `centre` the camera-space
/// centre.
CameraEllipsoid cameraEllipsoid(const EllipsoidInstance& ellipsoid, const glm::dmat3& cameraFromWorld,
                                const glm::dvec3& centre);

/// Half the extent of an ellipsoid along each camera axis (the box about its centre that holds it).
glm::dvec3 cameraHalfExtents(const CameraEllipsoid& ellipsoid);

// The rays r = (u, v, -1) through the image plane, whose parameter t is the planar eye depth of the point t
// r: each meets the ellipsoid scaled by s about its centre where |t M r - M c| = s, that is at t = (g.r -+
// sqrt(r^T K r)) / r^T A r with A = M^T M, g = M^T M c and the cone K = s^2 A - (C M)^T (C M), C the cross
// product with M c (r^T K r = s^2 |M r|^2 - |M c x M r|^2). Built from cross products, the discriminant's
// rounding grows with (distance / radius)^2 rather than its fourth power, as the textbook quadratic's
// cancelling terms would: a sun's view is a thousand liquid radii away, some 10^5 particle radii, where
// that leaves about 10^-6 of a chord, far inside the margins. For one pixel every ellipsoid is compared on
// the same ray.
// The ellipsoid grown and shrunk for the rounding margins differ in s alone, so A, g and B are kept once.
struct ChordPolynomials {
  glm::dmat3 lengths;  // A
  glm::dvec3 along;    // g
  glm::dmat3 crossed;  // B = (C M)^T (C M)

  ChordPolynomials() = default;  // uninitialised: a trivial type for the occlusion test's bulk storage
  explicit ChordPolynomials(const CameraEllipsoid& ellipsoid);
  // The cone K of the ellipsoid scaled by s.
  glm::dmat3 cone(double scale) const { return scale * scale * lengths - crossed; }
};

// r^T Q r along a row (r = (u, v, -1), v fixed) as q2 u^2 + q1 u + q0.
struct RowQuadratic {
  double q2 = 0.0, q1 = 0.0, q0 = 0.0;
  RowQuadratic(const glm::dmat3& q, double v)
      : q2(q[0][0]), q1(2.0 * (q[0][1] * v - q[0][2])), q0(q[1][1] * v * v - 2.0 * q[1][2] * v + q[2][2]) {}
  double at(double u) const { return (q2 * u + q1) * u + q0; }
};

// One ellipsoid's chords along one row of pixels, the ellipsoid scaled by `scale` about its centre.
struct RowChords {
  RowQuadratic lengths, cone;
  double alongSlope, alongOffset;
  RowChords(const ChordPolynomials& polynomials, double scale, double v)
      : lengths(polynomials.lengths, v),
        cone(polynomials.cone(scale), v),
        alongSlope(polynomials.along.x),
        alongOffset(polynomials.along.y * v - polynomials.along.z) {}
  // Where the ray at u enters and leaves (planar eye depths); false where it misses.
  bool at(double u, double& entry, double& exit) const {
    const double lengthSquared = lengths.at(u), missing = cone.at(u);
    if (!(missing >= 0.0) || !(lengthSquared > 0.0)) return false;
    const double along = alongSlope * u + alongOffset, half = std::sqrt(missing);
    const double inverseLength = 1.0 / lengthSquared;
    entry = (along - half) * inverseLength;
    exit = (along + half) * inverseLength;
    return true;
  }
};

/// A view's pixel grid: the rays (u, v, -1) through its pixel centres, and where a domain box clips them.
struct ViewGrid {
  int width = 0;
  int height = 0;
  float focal = 1.0f;  // pixels per unit of the image plane at distance 1
  // Where each pixel's ray enters and leaves a domain box, in planar eye depth; empty without a box.
  std::vector<double> boxEnter, boxLeave;

  explicit ViewGrid(const Camera& camera);
  // The ray through a pixel centre (x right, y down) is (u, v, -1) in camera space: looked up, as the
  // occlusion test asks for them at every row and pixel it visits (columnsU()[x] is u).
  double v(int y) const { return rowV_[std::size_t(y)]; }
  const double* columnsU() const { return columnU_.data(); }

  // Fills boxEnter and boxLeave (an affine map keeps a ray's parameter, so the slab test runs in the box's
  // frame).
  void clipToBox(const DomainBox& domain, const glm::dmat4& boxFromCamera);
  // The pixels of a row (clamped to [low, high]) whose centres' rays may meet an ellipsoid, from its cone's
  // quadratic along the row, widened by a hundredth of a pixel each side for rounding (a row the quadratic
  // cannot bound keeps [low, high]). Leaves first > last where the row misses it.
  void rowSpan(const RowQuadratic& cone, int low, int high, int& first, int& last) const;
  // The pixels whose centres may see a box about `centre` (camera space, wholly in front of the eye): its
  // corners projected, which bound its projection.
  void rectangle(const glm::vec3& centre, const glm::vec3& halfExtents, glm::ivec2& low,
                 glm::ivec2& high) const;
  // The window position (x right, y down) of a camera-space point in front of the eye.
  glm::vec2 pixelOf(const glm::vec3& point) const;

 private:
  std::vector<double> columnU_, rowV_;
};

inline void ViewGrid::rowSpan(const RowQuadratic& cone, int low, int high, int& first, int& last) const {
  first = low;
  last = high;
  if (!(cone.q2 < 0.0)) return;
  const double discriminant = 0.25 * cone.q1 * cone.q1 - cone.q2 * cone.q0;
  if (!(discriminant >= 0.0)) {
    if (discriminant < 0.0) first = high + 1;  // a NaN keeps the whole row
    return;
  }
  const double root = std::sqrt(discriminant);
  const double u0 = (-0.5 * cone.q1 + root) / cone.q2, u1 = (-0.5 * cone.q1 - root) / cone.q2;  // u0 <= u1
  // The pixels whose centres (x + 0.5 - width / 2) / focal lie in [u0, u1], widened by kSpanMargin pixels:
  // the roots' rounding is far below it (about 1e-8 of u where the row grazes the ellipsoid, 1e-5 pixels),
  // and an ellipsoid is grown (shrunk) by 1e-3 of itself for the GPU's rounding besides. A whole pixel each
  // side evaluated up to four pixels more per row than the 2-3 a small ellipsoid covers.
  constexpr double kSpanMargin = 0.01;
  const double x0 = std::ceil(u0 * focal + 0.5 * width - 0.5 - kSpanMargin);
  const double x1 = std::floor(u1 * focal + 0.5 * width - 0.5 + kSpanMargin);
  if (x0 > double(low)) first = x0 > double(high) ? high + 1 : int(x0);
  if (x1 < double(high)) last = x1 < double(low) ? low - 1 : int(x1);
}

}  // namespace spindrift::view_chords
