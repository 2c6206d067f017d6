#include "prep/OccludedAggregates.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include "prep/EllipsoidBounds.h"
#include "prep/LayerOrder.h"

namespace spindrift {
namespace {

// Margins for the rounding between this test and the impostor pass's float ray casts. A covering ellipsoid is
// shrunk and a possibly drawn one grown by kRadiusMargin of each semi-axis (and a ray's distance to a centre
// is trusted to kDirectionMargin of the centre's distance: a float ray direction's error); where a chord ends
// is trusted to kChordMargin of the bounding radius (a grazing ray's end is ill-conditioned) and
// kDistanceMargin of the distance.
constexpr double kRadiusMargin = 1e-3;
constexpr double kDirectionMargin = 1e-6;
constexpr double kChordMargin = 1e-2;
constexpr double kDistanceMargin = 1e-5;

// An ellipsoid in camera space, {x : |M (x - c)| <= 1}: the rows of M and M c.
struct CameraEllipsoid {
  glm::dvec3 rows[3];
  glm::dvec3 scaledCentre{0.0};
};

// The rays r = (u, v, -1) through the image plane, whose parameter t is the planar eye depth of the point t
// r: each meets the ellipsoid scaled by s about its centre where |t M r - M c| = s, that is at t = (g.r -+
// sqrt(r^T K r)) / r^T A r with A = M^T M, g = M^T M c and the cone K = s^2 A - (C M)^T (C M), C the cross
// product with M c (r^T K r = s^2 |M r|^2 - |M c x M r|^2). Built from cross products, the discriminant's
// rounding grows with (distance / radius)^2 rather than its fourth power, as the textbook quadratic's
// cancelling terms would: a sun's view is a thousand liquid radii away, some 10^5 particle radii, where that
// leaves about 10^-6 of a chord, far inside the margins. For one pixel every ellipsoid is compared on the
// same ray.
struct ChordPolynomials {
  glm::dmat3 lengths{0.0};  // A
  glm::dvec3 along{0.0};    // g
  glm::dmat3 cone{0.0};     // K

  ChordPolynomials() = default;
  ChordPolynomials(const CameraEllipsoid& ellipsoid, double scale) {
    glm::dvec3 columns[3], crossed[3];
    for (int j = 0; j < 3; ++j) {
      columns[j] = glm::dvec3(ellipsoid.rows[0][j], ellipsoid.rows[1][j], ellipsoid.rows[2][j]);
      crossed[j] = glm::cross(ellipsoid.scaledCentre, columns[j]);
      along[j] = glm::dot(columns[j], ellipsoid.scaledCentre);
    }
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        lengths[j][k] = glm::dot(columns[j], columns[k]);
        cone[j][k] = scale * scale * lengths[j][k] - glm::dot(crossed[j], crossed[k]);
      }
  }
};

// r^T Q r along a row (r = (u, v, -1), v fixed) as q2 u^2 + q1 u + q0.
struct RowQuadratic {
  double q2 = 0.0, q1 = 0.0, q0 = 0.0;
  RowQuadratic(const glm::dmat3& q, double v)
      : q2(q[0][0]), q1(2.0 * (q[0][1] * v - q[0][2])), q0(q[1][1] * v * v - 2.0 * q[1][2] * v + q[2][2]) {}
  double at(double u) const { return (q2 * u + q1) * u + q0; }
};

// One ellipsoid's chords along one row of pixels.
struct RowChords {
  RowQuadratic lengths, cone;
  double alongSlope, alongOffset;
  RowChords(const ChordPolynomials& polynomials, double v)
      : lengths(polynomials.lengths, v),
        cone(polynomials.cone, v),
        alongSlope(polynomials.along.x),
        alongOffset(polynomials.along.y * v - polynomials.along.z) {}
  // Where the ray at u enters and leaves (planar eye depths); false where it misses.
  bool at(double u, double& entry, double& exit) const {
    const double lengthSquared = lengths.at(u), missing = cone.at(u);
    if (!(missing >= 0.0) || !(lengthSquared > 0.0)) return false;
    const double along = alongSlope * u + alongOffset, half = std::sqrt(missing);
    entry = (along - half) / lengthSquared;
    exit = (along + half) / lengthSquared;
    return true;
  }
};

// One ellipsoid as this view sees it: grown by the margins, where a pixel's ray meets it (it may be drawn
// there, no nearer than that entry and no farther than that exit); shrunk by them, where it certainly is
// (entering no later and leaving no earlier).
struct ViewedEllipsoid {
  CameraEllipsoid ellipsoid;
  double grown = 1.0, shrunk = 0.0;  // the scales about its centre
  double chordMargin = 0.0;
  // Bounds on any ray's entry and exit of the grown ellipsoid, margins included: its bounding sphere's
  // depths.
  double nearest = 0.0, farthest = 0.0;
  ChordPolynomials grownChords, shrunkChords;
  glm::ivec2 reachLow{0}, reachHigh{-1};  // pixel rectangles (inclusive) of the grown and the shrunk one
  glm::ivec2 coverLow{0}, coverHigh{-1};
  bool valid = false;  // whole between the near and far planes
};

// The ellipsoid in camera space.
CameraEllipsoid cameraEllipsoid(const EllipsoidInstance& ellipsoid, const glm::dmat3& cameraFromWorld,
                                const glm::dvec3& centre) {
  CameraEllipsoid result;
  for (int k = 0; k < 3; ++k) {
    result.rows[k] = cameraFromWorld * glm::dvec3(glm::vec3(ellipsoid.inverseAxesRows[k]));
    result.scaledCentre[k] = glm::dot(result.rows[k], centre);
  }
  return result;
}

// Half the extent of an ellipsoid along each camera axis (the box about its centre that holds it): along a
// unit e it reaches |M^-T e|, and M^-T = M (M^T M)^-1 is M with each row divided by its squared length,
// the rows being orthogonal.
glm::dvec3 cameraHalfExtents(const CameraEllipsoid& ellipsoid) {
  glm::dvec3 squared(0.0);
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 axis = ellipsoid.rows[k] / glm::dot(ellipsoid.rows[k], ellipsoid.rows[k]);
    squared += axis * axis;
  }
  return glm::sqrt(squared);
}

struct ViewGrid {
  int width = 0;
  int height = 0;
  float focal = 1.0f;  // pixels per unit of the image plane at distance 1

  explicit ViewGrid(const Camera& camera) : width(camera.width), height(camera.height) {
    focal = 1.0f / camera.pixelSizeAt(1.0f);
  }
  // The ray through a pixel centre (x right, y down) is (u, v, -1) in camera space.
  double u(int x) const { return (x + 0.5 - 0.5 * width) / focal; }
  double v(int y) const { return (0.5 * height - (y + 0.5)) / focal; }

  // Where each pixel's ray enters and leaves a domain box, in planar eye depth (an affine map keeps a ray's
  // parameter, so the slab test runs in the box's frame); without a box every ray is inside it.
  std::vector<double> boxEnter, boxLeave;
  void clipToBox(const DomainBox& domain, const glm::dmat4& boxFromCamera) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    boxEnter.assign(pixels, 0.0);
    boxLeave.assign(pixels, 0.0);
    const glm::dvec3 origin(boxFromCamera[3]), low(domain.low), high(domain.high);
    for (std::size_t pixel = 0; pixel < pixels; ++pixel) {
      const glm::dvec3 ray(u(int(pixel % std::size_t(width))), v(int(pixel / std::size_t(width))), -1.0);
      const glm::dvec3 direction = glm::dmat3(boxFromCamera) * ray;
      double enter = -std::numeric_limits<double>::infinity(),
             leave = std::numeric_limits<double>::infinity();
      for (int axis = 0; axis < 3; ++axis) {
        if (direction[axis] == 0.0) {
          if (origin[axis] < low[axis] || origin[axis] > high[axis]) enter = leave = 0.0;  // misses the slab
          continue;
        }
        const double a = (low[axis] - origin[axis]) / direction[axis];
        const double b = (high[axis] - origin[axis]) / direction[axis];
        enter = std::max(enter, std::min(a, b));
        leave = std::min(leave, std::max(a, b));
      }
      boxEnter[pixel] = enter;
      boxLeave[pixel] = leave;
    }
  }
  // A chord clipped to the box, as the impostor pass clips it (lib/ellipsoid_ray.glsl).
  void clip(std::size_t pixel, double& entry, double& exit) const {
    if (boxEnter.empty()) return;
    entry = std::max(entry, boxEnter[pixel]);
    exit = std::min(exit, boxLeave[pixel]);
  }
  // The window position (x right, y down) of a camera-space point in front of the eye.
  glm::vec2 pixelOf(const glm::vec3& point) const {
    return {0.5f * width + focal * point.x / -point.z, 0.5f * height - focal * point.y / -point.z};
  }

  // The pixels of a row (clamped to [low, high]) whose centres' rays may meet an ellipsoid, from its cone's
  // quadratic along the row, widened by a pixel each side for rounding (a row the quadratic cannot bound
  // keeps [low, high]). Leaves first > last where the row misses it.
  void rowSpan(const RowQuadratic& cone, int low, int high, int& first, int& last) const {
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
    const double x0 = std::floor(u0 * focal + 0.5 * width - 0.5) - 1.0;
    const double x1 = std::ceil(u1 * focal + 0.5 * width - 0.5) + 1.0;
    if (x0 > double(low)) first = x0 > double(high) ? high + 1 : int(x0);
    if (x1 < double(high)) last = x1 < double(low) ? low - 1 : int(x1);
  }

  // The pixels whose centres may see a box about `centre` (camera space, wholly in front of the eye): its
  // corners projected, which bound its projection.
  void rectangle(const glm::vec3& centre, const glm::vec3& halfExtents, glm::ivec2& low,
                 glm::ivec2& high) const {
    glm::vec2 least(std::numeric_limits<float>::max()), most(std::numeric_limits<float>::lowest());
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 point =
          centre + halfExtents * glm::vec3(corner & 1 ? 1.0f : -1.0f, corner & 2 ? 1.0f : -1.0f,
                                           corner & 4 ? 1.0f : -1.0f);
      const glm::vec2 pixel = pixelOf(point);
      least = glm::min(least, pixel);
      most = glm::max(most, pixel);
    }
    // Pixel centres at +0.5 inside [least, most], widened by one pixel for rounding; clamped to just outside
    // the frame first, so that a ball close to the eye plane cannot overflow the conversion to int.
    const glm::vec2 outside(-2.0f), beyond(float(width) + 2.0f, float(height) + 2.0f);
    least = glm::clamp(least, outside, beyond);
    most = glm::clamp(most, outside, beyond);
    low = glm::max(glm::ivec2(glm::floor(least - 0.5f)) - 1, glm::ivec2(0));
    high = glm::min(glm::ivec2(glm::ceil(most - 0.5f)) + 1, glm::ivec2(width - 1, height - 1));
  }
};

}  // namespace

OccludedAggregatesResult dropOccludedAggregates(std::vector<EllipsoidInstance>& ellipsoids, LayerSplit& split,
                                                const Camera& camera, const DomainBox* domain,
                                                const SolidDepthTiles* solids) {
  const auto start = std::chrono::steady_clock::now();
  OccludedAggregatesResult result;
  const std::size_t count = ellipsoids.size();
  if (count == 0 || camera.width <= 0 || camera.height <= 0) return result;
  ViewGrid grid(camera);
  const glm::mat4 cameraFromWorld = camera.cameraFromWorld();
  const glm::dmat3 rotation = glm::dmat3(glm::mat3(cameraFromWorld));
  if (domain)
    grid.clipToBox(*domain,
                   glm::inverse(glm::dmat4(domain->worldFromBox)) * glm::dmat4(camera.worldFromCamera));

  std::vector<ViewedEllipsoid> viewed(count);
  std::vector<char> covers(count, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const glm::vec4& sphere = ellipsoids[i].centreAndBoundingRadius;
      const glm::vec3 centre = glm::vec3(cameraFromWorld * glm::vec4(glm::vec3(sphere), 1.0f));
      const float radius = sphere.w, depth = -centre.z, distance = glm::length(centre);
      if (!(depth - radius > camera.nearClip) || !(depth + radius < camera.farClip) || !(distance > radius))
        continue;
      ViewedEllipsoid& view = viewed[i];
      view.valid = true;
      // Every semi-axis grown, or shrunk, by kRadiusMargin of itself and by the slack at least.
      const double slack = kDirectionMargin * double(distance);
      const double shortest = double(inscribedRadius(ellipsoids[i]));
      view.ellipsoid = cameraEllipsoid(ellipsoids[i], rotation, glm::dvec3(centre));
      const glm::dvec3 halfExtents = cameraHalfExtents(view.ellipsoid);
      view.grown = 1.0 + kRadiusMargin + slack / shortest;
      view.chordMargin = kChordMargin * double(radius) + kDistanceMargin * double(distance);
      view.nearest = double(depth) - view.grown * double(radius) - 2.0 * view.chordMargin;
      view.farthest = double(depth) + view.grown * double(radius) + 2.0 * view.chordMargin;
      grid.rectangle(centre, glm::vec3(view.grown * halfExtents), view.reachLow, view.reachHigh);
      view.grownChords = ChordPolynomials(view.ellipsoid, view.grown);
      view.shrunk = 1.0 - kRadiusMargin - slack / shortest;
      view.shrunkChords = ChordPolynomials(view.ellipsoid, view.shrunk);
      if (!(view.shrunk > 0.0)) continue;
      grid.rectangle(centre, glm::vec3(view.shrunk * halfExtents), view.coverLow, view.coverHigh);
      covers[i] = 1;
    }
  });

  // How far along each pixel's ray the front layer's surface lies at most, and the back layer's at least:
  // each covering ellipsoid bounds them by its shrunk self's chord. In bands of rows, so that each pixel
  // is written by one thread.
  const std::size_t pixels = std::size_t(grid.width) * grid.height;
  std::vector<double> frontAtMost(pixels, std::numeric_limits<double>::infinity());
  std::vector<double> backAtLeast(pixels, -std::numeric_limits<double>::infinity());
  // Where a layer's ellipsoid certainly reaches past the box's face, that layer's surface is the face itself,
  // computed by every fragment there from the pixel's ray alone: nothing can be nearer (farther), the others
  // that reach past it tie, and the impostor pass gives the face any exact tie with an ellipsoid's own
  // surface (ellipsoid_impostor.frag). The first one met keeps the pixel; the others need not be drawn there.
  constexpr std::uint32_t kNoOwner = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> frontFaceOwner, backFaceOwner;
  if (domain) {
    frontFaceOwner.assign(pixels, kNoOwner);
    backFaceOwner.assign(pixels, kNoOwner);
  }
  const std::size_t backFrom = count - split.backOnly;
  constexpr int kRowsPerBand = 16;
  const int bands = (grid.height + kRowsPerBand - 1) / kRowsPerBand;
  // Nearest first: once a pixel's nearer surfaces are in, a farther ellipsoid that can change neither bound
  // there (nor take a face it cannot reach) is passed over without its chord.
  std::vector<std::uint32_t> nearestFirst;
  nearestFirst.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
    if (covers[i]) nearestFirst.push_back(std::uint32_t(i));
  std::sort(nearestFirst.begin(), nearestFirst.end(),
            [&](std::uint32_t a, std::uint32_t b) { return viewed[a].nearest < viewed[b].nearest; });
  // Each band's ellipsoids, in that order: a band touches only the few it holds.
  std::vector<std::vector<std::uint32_t>> inBand(static_cast<std::size_t>(bands));
  for (const std::uint32_t i : nearestFirst) {
    const int first = std::max(viewed[i].coverLow.y, 0) / kRowsPerBand;
    const int last = std::min(viewed[i].coverHigh.y / kRowsPerBand, bands - 1);
    for (int band = first; band <= last; ++band)
      inBand[std::size_t(band)].push_back(i);
  }
  tbb::parallel_for(0, bands, [&](int band) {
    const int firstRow = band * kRowsPerBand, lastRow = std::min(firstRow + kRowsPerBand, grid.height) - 1;
    for (const std::uint32_t i : inBand[std::size_t(band)]) {
      const ViewedEllipsoid& view = viewed[i];
      for (int y = std::max(view.coverLow.y, firstRow); y <= std::min(view.coverHigh.y, lastRow); ++y) {
        int firstX, lastX;
        const RowChords row(view.shrunkChords, grid.v(y));
        grid.rowSpan(row.cone, view.coverLow.x, view.coverHigh.x, firstX, lastX);
        for (int x = firstX; x <= lastX; ++x) {
          const std::size_t here = std::size_t(y) * grid.width + x;
          const bool frontSettled =
              domain ? frontFaceOwner[here] != kNoOwner ||
                           (frontAtMost[here] <= view.nearest && view.nearest >= grid.boxEnter[here])
                     : frontAtMost[here] <= view.nearest;
          const bool backSettled =
              domain ? backFaceOwner[here] != kNoOwner ||
                           (backAtLeast[here] >= view.farthest && view.farthest <= grid.boxLeave[here])
                     : backAtLeast[here] >= view.farthest;
          if (frontSettled && backSettled) continue;
          double entry, exit;
          if (!row.at(grid.u(x), entry, exit)) continue;
          const std::size_t pixel = std::size_t(y) * grid.width + x;
          // Where a domain box cuts it, its surfaces are the clipped chord's ends, if any are left.
          const double unclippedEntry = entry, unclippedExit = exit;
          grid.clip(pixel, entry, exit);
          const bool clipped = entry != unclippedEntry || exit != unclippedExit;
          if (clipped && !(entry < exit - 2.0 * view.chordMargin)) continue;
          // It covers the back layer only where its front lies before the solids (the impostor pass hides
          // it where its entry lies behind one).
          const bool coversBackHere = !solids || entry + view.chordMargin < double(solids->nearestAt(x, y));
          frontAtMost[pixel] = std::min(frontAtMost[pixel], entry + view.chordMargin);
          if (coversBackHere) backAtLeast[pixel] = std::max(backAtLeast[pixel], exit - view.chordMargin);
          if (!domain) continue;
          const std::uint32_t index = std::uint32_t(i);
          if (i < backFrom && frontFaceOwner[pixel] == kNoOwner &&
              unclippedEntry < grid.boxEnter[pixel] - 2.0 * view.chordMargin)
            frontFaceOwner[pixel] = index;
          if (coversBackHere && i >= split.frontOnly && backFaceOwner[pixel] == kNoOwner &&
              unclippedExit > grid.boxLeave[pixel] + 2.0 * view.chordMargin)
            backFaceOwner[pixel] = index;
        }
      }
    }
  });

  // An ellipsoid is hidden from a layer when at every pixel where it may be drawn, another ellipsoid's
  // surface is certainly nearer than its grown self's entry (front) or farther than its exit (back), or
  // another one holds the box's face there. Its own shrunk self never hides it: that chord lies inside the
  // grown one's, and the margins only widen that; a face's owner is never hidden where it owns it.
  std::vector<char> inFront(count), inBack(count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      inFront[i] = i < backFrom;
      inBack[i] = i >= split.frontOnly;
      const ViewedEllipsoid& view = viewed[i];
      if (!view.valid) continue;
      bool hiddenFront = inFront[i], hiddenBack = inBack[i];
      // No ray meets the grown ellipsoid nearer than its bounding sphere's near side or farther than its far
      // side: where those alone settle a pixel (deep inside a body, most pixels), no chord is needed.
      for (int y = view.reachLow.y; y <= view.reachHigh.y && (hiddenFront || hiddenBack); ++y) {
        int firstX, lastX;
        const RowChords row(view.grownChords, grid.v(y));
        grid.rowSpan(row.cone, view.reachLow.x, view.reachHigh.x, firstX, lastX);
        for (int x = firstX; x <= lastX && (hiddenFront || hiddenBack); ++x) {
          const std::size_t pixel = std::size_t(y) * grid.width + x;
          const bool frontTie = domain && frontFaceOwner[pixel] != kNoOwner && frontFaceOwner[pixel] != i;
          const bool backTie = domain && backFaceOwner[pixel] != kNoOwner && backFaceOwner[pixel] != i;
          const bool frontSettled = !hiddenFront || frontTie || frontAtMost[pixel] < view.nearest;
          const bool backSettled = !hiddenBack || backTie || backAtLeast[pixel] > view.farthest;
          if (frontSettled && backSettled) continue;
          double entry, exit;
          if (!row.at(grid.u(x), entry, exit)) continue;
          grid.clip(pixel, entry, exit);
          if (entry > exit + 2.0 * view.chordMargin) continue;  // the box leaves nothing of it here
          hiddenFront = hiddenFront && (frontTie || frontAtMost[pixel] < entry - view.chordMargin);
          hiddenBack = hiddenBack && (backTie || backAtLeast[pixel] > exit + view.chordMargin);
        }
      }
      if (hiddenFront) inFront[i] = 0;
      if (hiddenBack) inBack[i] = 0;
    }
  });

  for (std::size_t i = 0; i < count; ++i) {
    result.hiddenFromFront += i < backFrom && !inFront[i];
    result.hiddenFromBack += i >= split.frontOnly && !inBack[i];
  }
  split = orderByLayers(ellipsoids, inFront, inBack);
  result.dropped = count - ellipsoids.size();
  result.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace spindrift
