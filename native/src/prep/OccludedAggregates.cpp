#include "prep/OccludedAggregates.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <type_traits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include "prep/AscendingOrder.h"
#include "prep/EllipsoidBounds.h"
#include "prep/LayerOrder.h"
#include "prep/OcclusionRows.h"
#include "prep/ViewChords.h"

namespace spindrift {
namespace {

using view_chords::cameraEllipsoid;
using view_chords::CameraEllipsoid;
using view_chords::cameraHalfExtents;
using view_chords::ChordPolynomials;
using view_chords::RowChords;
using view_chords::ViewGrid;

// Margins for the rounding between this test and the impostor pass's float ray casts. A covering ellipsoid is
// shrunk and a possibly drawn one grown by kRadiusMargin of each semi-axis (and a ray's distance to a centre
// is trusted to kDirectionMargin of the centre's distance: a float ray direction's error); where a chord ends
// is trusted to kChordMargin of the bounding radius (a grazing ray's end is ill-conditioned) and
// kDistanceMargin of the distance.
constexpr double kRadiusMargin = 1e-3;
constexpr double kDirectionMargin = 1e-6;
constexpr double kChordMargin = 1e-2;
constexpr double kDistanceMargin = 1e-5;

// One ellipsoid as this view sees it: grown by the margins, where a pixel's ray meets it (it may be drawn
// there, no nearer than that entry and no farther than that exit); shrunk by them, where it certainly is
// (entering no later and leaving no earlier). A trivial type, left uninitialised until the threads that
// compute the views fill it, so that they touch fresh pages first: 248 bytes an ellipsoid, 37 MB for the
// benchmark's bigger bake, whose page faults took 18 ms in one thread value-initialising them (and an
// OcclusionWorkspace keeps them for the next call). `valid` is set for every ellipsoid, the rest for a valid
// one (the cover rectangle where it covers).
struct ViewedEllipsoid {
  double grown, shrunk;  // the scales about its centre
  double chordMargin;
  // Bounds on any ray's entry and exit of the grown ellipsoid, margins included: its bounding sphere's
  // depths.
  double nearest, farthest;
  ChordPolynomials chords;
  glm::ivec2 reachLow, reachHigh;  // pixel rectangles (inclusive) of the grown and the shrunk one
  glm::ivec2 coverLow, coverHigh;
  bool valid;  // whole between the near and far planes
};
static_assert(std::is_trivially_default_constructible_v<ViewedEllipsoid>);

// The bands take their ellipsoids nearest first, at random places in the views' memory (tens of megabytes on
// a bigger bake): each view is asked for this many ellipsoids ahead, so that its cache lines arrive while
// the ones before are worked on.
constexpr std::size_t kPrefetchDistance = 4;

void prefetchView(const ViewedEllipsoid& view) {
  const char* const bytes = reinterpret_cast<const char*>(&view);
  for (std::size_t offset = 0; offset < sizeof(ViewedEllipsoid); offset += 64)
    __builtin_prefetch(bytes + offset);
  __builtin_prefetch(bytes + sizeof(ViewedEllipsoid) - 1);
}

}  // namespace

struct OcclusionWorkspace::Views {
  std::unique_ptr<ViewedEllipsoid[]> views;
  std::size_t capacity = 0;

  // Room for `count` views: the memory of the call before where it is enough.
  ViewedEllipsoid* reserve(std::size_t count) {
    if (count > capacity) {
      views.reset();  // the old pages go before the new ones are faulted in
      views.reset(new ViewedEllipsoid[count]);
      capacity = count;
    }
    return views.get();
  }
};

OcclusionWorkspace::OcclusionWorkspace() : views_(std::make_unique<Views>()) {}
OcclusionWorkspace::~OcclusionWorkspace() = default;
OcclusionWorkspace::OcclusionWorkspace(OcclusionWorkspace&&) noexcept = default;
OcclusionWorkspace& OcclusionWorkspace::operator=(OcclusionWorkspace&&) noexcept = default;
std::size_t OcclusionWorkspace::capacity() const {
  return views_ ? views_->capacity : 0;
}

OccludedAggregatesResult dropOccludedAggregates(std::vector<EllipsoidInstance>& ellipsoids, LayerSplit& split,
                                                const Camera& camera, const DomainBox* domain,
                                                const SolidDepthTiles* solids,
                                                OcclusionWorkspace* workspace) {
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

  OcclusionWorkspace::Views ownViews;
  OcclusionWorkspace::Views& views = workspace && workspace->views_ ? *workspace->views_ : ownViews;
  ViewedEllipsoid* const viewed = views.reserve(count);
  std::vector<char> covers(count, 0);
  // The rows of each covering ellipsoid's cover rectangle and its nearest depth, apart from its view: the
  // depth order is built from these, and the bands filled in it read them at random; 16 bytes an ellipsoid
  // stay in the caches where 248 do not (the bigger bake's bands took 7 to 12 ms reading the views).
  std::vector<glm::ivec2> coverRows(count);
  std::vector<double> coverNearest(count);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      ViewedEllipsoid& view = viewed[i];
      const glm::vec4& sphere = ellipsoids[i].centreAndBoundingRadius;
      const glm::vec3 centre = glm::vec3(cameraFromWorld * glm::vec4(glm::vec3(sphere), 1.0f));
      const float radius = sphere.w, depth = -centre.z, distance = glm::length(centre);
      view.valid = depth - radius > camera.nearClip && depth + radius < camera.farClip && distance > radius;
      if (!view.valid) continue;
      // Every semi-axis grown, or shrunk, by kRadiusMargin of itself and by the slack at least.
      const double slack = kDirectionMargin * double(distance);
      const double shortest = double(inscribedRadius(ellipsoids[i]));
      const CameraEllipsoid ellipsoid = cameraEllipsoid(ellipsoids[i], rotation, glm::dvec3(centre));
      const glm::dvec3 halfExtents = cameraHalfExtents(ellipsoid);
      view.chords = ChordPolynomials(ellipsoid);
      view.grown = 1.0 + kRadiusMargin + slack / shortest;
      view.chordMargin = kChordMargin * double(radius) + kDistanceMargin * double(distance);
      view.nearest = double(depth) - view.grown * double(radius) - 2.0 * view.chordMargin;
      view.farthest = double(depth) + view.grown * double(radius) + 2.0 * view.chordMargin;
      grid.rectangle(centre, glm::vec3(view.grown * halfExtents), view.reachLow, view.reachHigh);
      view.shrunk = 1.0 - kRadiusMargin - slack / shortest;
      if (!(view.shrunk > 0.0)) continue;
      grid.rectangle(centre, glm::vec3(view.shrunk * halfExtents), view.coverLow, view.coverHigh);
      covers[i] = 1;
      coverRows[i] = {view.coverLow.y, view.coverHigh.y};
      coverNearest[i] = view.nearest;
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
  using occlusion_rows::kNoOwner;
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
  // Ties in the index's order.
  std::vector<std::uint32_t> covering;
  std::vector<double> coveringDepths;
  covering.reserve(count);
  coveringDepths.reserve(count);
  for (std::size_t i = 0; i < count; ++i)
    if (covers[i]) {
      covering.push_back(std::uint32_t(i));
      coveringDepths.push_back(coverNearest[i]);
    }
  const std::vector<std::uint32_t> order = ascendingOrder(coveringDepths);
  std::vector<std::uint32_t> nearestFirst(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    nearestFirst[k] = covering[order[k]];
  // Each band's ellipsoids, in that order: a band touches only the few it holds.
  std::vector<std::vector<std::uint32_t>> inBand(static_cast<std::size_t>(bands));
  for (const std::uint32_t i : nearestFirst) {
    const int first = std::max(coverRows[i].x, 0) / kRowsPerBand;
    const int last = std::min(coverRows[i].y / kRowsPerBand, bands - 1);
    for (int band = first; band <= last; ++band)
      inBand[std::size_t(band)].push_back(i);
  }
  // The solids' depths by pixel, for the rows' contiguous loads.
  std::vector<double> solidNearest, solidFarthest;
  if (solids) {
    solidNearest.resize(pixels);
    solidFarthest.resize(pixels);
    for (int y = 0; y < grid.height; ++y)
      for (int x = 0; x < grid.width; ++x) {
        const std::size_t pixel = std::size_t(y) * grid.width + x;
        solidNearest[pixel] = solids->nearestAt(x, y);
        solidFarthest[pixel] = solids->farthestAt(pixel);
      }
  }
  const auto rowBounds = [&](int y) {
    const std::size_t rowStart = std::size_t(y) * grid.width;
    occlusion_rows::RowBounds bounds;
    bounds.frontAtMost = frontAtMost.data() + rowStart;
    bounds.backAtLeast = backAtLeast.data() + rowStart;
    if (domain) {
      bounds.boxEnter = grid.boxEnter.data() + rowStart;
      bounds.boxLeave = grid.boxLeave.data() + rowStart;
      bounds.frontFaceOwner = frontFaceOwner.data() + rowStart;
      bounds.backFaceOwner = backFaceOwner.data() + rowStart;
    }
    if (solids) {
      bounds.solidNearest = solidNearest.data() + rowStart;
      bounds.solidFarthest = solidFarthest.data() + rowStart;
    }
    return bounds;
  };
  tbb::parallel_for(0, bands, [&](int band) {
    const int firstRow = band * kRowsPerBand, lastRow = std::min(firstRow + kRowsPerBand, grid.height) - 1;
    const std::vector<std::uint32_t>& members = inBand[std::size_t(band)];
    for (std::size_t k = 0; k < members.size(); ++k) {
      if (k + kPrefetchDistance < members.size()) prefetchView(viewed[members[k + kPrefetchDistance]]);
      const std::uint32_t i = members[k];
      const ViewedEllipsoid& view = viewed[i];
      const occlusion_rows::Cover cover{
          i, view.nearest, view.farthest, view.chordMargin, i < backFrom, i >= split.frontOnly};
      for (int y = std::max(view.coverLow.y, firstRow); y <= std::min(view.coverHigh.y, lastRow); ++y) {
        int firstX, lastX;
        const RowChords row(view.chords, view.shrunk, grid.v(y));
        grid.rowSpan(row.cone, view.coverLow.x, view.coverHigh.x, firstX, lastX);
        occlusion_rows::coverRow(row, grid.columnsU(), firstX, lastX, cover, rowBounds(y));
      }
    }
  });

  // An ellipsoid is hidden from a layer when at every pixel where it may be drawn, another ellipsoid's
  // surface is certainly nearer than its grown self's entry (front) or farther than its exit (back), or
  // another one holds the box's face there. Its own shrunk self never hides it: that chord lies inside the
  // grown one's, and the margins only widen that; a face's owner is never hidden where it owns it. Where it
  // is shown, the rectangle of those pixels is all the impostor pass needs to draw of it in that layer: at
  // every other pixel a surface it cannot beat is drawn (the pixel's winner is shown there). Those rectangles
  // are a few hundredths of the ellipsoids' own on the dam break (docs/frame-cost.md, session 41).
  std::vector<char> inFront(count), inBack(count);
  std::vector<std::uint64_t> reachPixels(count, 0), shownPixels(count, 0);  // summed below, in order
  const bool packable = grid.width < 0xffff && grid.height < 0xffff;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      inFront[i] = i < backFrom;
      inBack[i] = i >= split.frontOnly;
      ellipsoids[i].shownRectangles = glm::uvec4(EllipsoidInstance::kShownEverywhere);
      const ViewedEllipsoid& view = viewed[i];
      if (!view.valid) continue;
      // No ray meets the grown ellipsoid nearer than its bounding sphere's near side or farther than its far
      // side: where those alone settle a pixel (deep inside a body, most pixels), no chord is needed.
      const occlusion_rows::Cover cover{std::uint32_t(i), view.nearest, view.farthest, view.chordMargin};
      occlusion_rows::ShownSpan frontColumns, backColumns, frontRows, backRows;
      for (int y = view.reachLow.y; y <= view.reachHigh.y; ++y) {
        int firstX, lastX;
        const RowChords row(view.chords, view.grown, grid.v(y));
        grid.rowSpan(row.cone, view.reachLow.x, view.reachHigh.x, firstX, lastX);
        occlusion_rows::ShownSpan front, back;
        occlusion_rows::shownRow(row, grid.columnsU(), firstX, lastX, cover, rowBounds(y), inFront[i],
                                 inBack[i], front, back);
        if (!front.empty()) {
          frontColumns.add(front.first);
          frontColumns.add(front.last);
          frontRows.add(y);
        }
        if (!back.empty()) {
          backColumns.add(back.first);
          backColumns.add(back.last);
          backRows.add(y);
        }
      }
      inFront[i] = inFront[i] && !frontRows.empty();
      inBack[i] = inBack[i] && !backRows.empty();
      const auto area = [](const glm::ivec2& low, const glm::ivec2& high) {
        return std::uint64_t(std::max(high.x - low.x + 1, 0)) *
               std::uint64_t(std::max(high.y - low.y + 1, 0));
      };
      const int layers = int(inFront[i]) + int(inBack[i]);
      reachPixels[i] = std::uint64_t(layers) * area(view.reachLow, view.reachHigh);
      shownPixels[i] =
          (inFront[i] ? area({frontColumns.first, frontRows.first}, {frontColumns.last, frontRows.last})
                      : 0) +
          (inBack[i] ? area({backColumns.first, backRows.first}, {backColumns.last, backRows.last}) : 0);
      // In the window's rows (y up), where a pixel index fits a rectangle's 16 bits.
      glm::uvec4& shown = ellipsoids[i].shownRectangles;
      if (!packable) continue;
      // A layer it is not in gets an empty rectangle: a draw of both layers at once (the sky's depth range)
      // draws it over the other layer's alone.
      const std::uint32_t nowhere = packPixelRange(1, 0);
      shown.x = inFront[i] ? packPixelRange(frontColumns.first, frontColumns.last) : nowhere;
      shown.y = inFront[i]
                    ? packPixelRange(grid.height - 1 - frontRows.last, grid.height - 1 - frontRows.first)
                    : nowhere;
      shown.z = inBack[i] ? packPixelRange(backColumns.first, backColumns.last) : nowhere;
      shown.w = inBack[i] ? packPixelRange(grid.height - 1 - backRows.last, grid.height - 1 - backRows.first)
                          : nowhere;
    }
  });

  for (std::size_t i = 0; i < count; ++i) {
    result.hiddenFromFront += i < backFrom && !inFront[i];
    result.hiddenFromBack += i >= split.frontOnly && !inBack[i];
    result.reachPixels += reachPixels[i];
    result.shownPixels += shownPixels[i];
  }
  split = orderByLayers(ellipsoids, inFront, inBack);
  result.dropped = count - ellipsoids.size();
  result.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace spindrift
