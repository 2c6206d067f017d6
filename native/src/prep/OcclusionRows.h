#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>

#include "prep/ViewChords.h"

// The occlusion test's work along one row of a view (prep/OccludedAggregates.cpp): what one covering
// ellipsoid does to the layer bounds (its shrunk chord's entry bounds the front layer there, its exit the
// back layer, and where it reaches past a domain box's face it may own that face), and where the bounds
// still show one ellipsoid in each layer.
namespace spindrift::occlusion_rows {

constexpr std::uint32_t kNoOwner = std::numeric_limits<std::uint32_t>::max();

// A view's bounds and what settles them, each array one value per pixel of the row (indexed by x).
struct RowBounds {
  double* frontAtMost = nullptr;  // the front layer's surface lies no farther
  double* backAtLeast = nullptr;  // the back layer's surface lies no nearer
  // With a domain box: where each pixel's ray enters and leaves it, and which ellipsoid owns its faces
  // (kNoOwner); all null without one.
  const double* boxEnter = nullptr;
  const double* boxLeave = nullptr;
  std::uint32_t* frontFaceOwner = nullptr;
  std::uint32_t* backFaceOwner = nullptr;
  // With solids: the depth no solid is nearer than (SolidDepthTiles::nearestAt) and the one a solid lies at
  // or nearer than (farthestAt); null without.
  const double* solidNearest = nullptr;
  const double* solidFarthest = nullptr;
};

// The ellipsoid as the row sees it.
struct Cover {
  std::uint32_t index = 0;
  double nearest = 0.0, farthest = 0.0;  // its grown bounding sphere's depths, margins included
  double chordMargin = 0.0;
  bool mayOwnFront = false, mayOwnBack = false;  // it is in that layer
};

// How the row is walked: AVX-512, eight pixels at a time and every unsettled pixel's chord computed, where
// the CPU has it and the row is longer than a pixel; else pixel by pixel, skipping the chord where the bounds
// already settle a pixel. Both give the same bounds, owners and shown spans to the bit.
enum class Walk { Fastest, Portable };

/// Lowers frontAtMost to the chord's entry and raises backAtLeast to its exit (each by the margin) over the
/// pixels [firstX, lastX] of the row, whose rays are (u[x], v, -1), as prep/OccludedAggregates.cpp
/// explains; `row` is the shrunk ellipsoid's chords along the row.
void coverRow(const view_chords::RowChords& row, const double* u, int firstX, int lastX, const Cover& cover,
              const RowBounds& bounds, Walk walk = Walk::Fastest);

/// The pixels of a row where an ellipsoid is shown in a layer: the first and last (first > last while none).
struct ShownSpan {
  int first = std::numeric_limits<int>::max();
  int last = std::numeric_limits<int>::min();
  void add(int x) {
    first = std::min(first, x);
    last = std::max(last, x);
  }
  bool empty() const { return first > last; }
};

/// Widens `front` (`back`) by the pixels of [firstX, lastX] where an ellipsoid in the front (back) layer
/// (`inFront`, `inBack`) is shown: where it may be drawn (`row`: its grown chords) and no other surface is
/// certainly nearer than its entry (farther than its exit), no other ellipsoid holds the box's face and no
/// solid hides it. At the pixels outside them another surface certainly wins the layer, so it need not be
/// drawn there; where neither layer shows it at any pixel, it is hidden. `cover.index` is the ellipsoid's;
/// the bounds are read, not written.
void shownRow(const view_chords::RowChords& row, const double* u, int firstX, int lastX, const Cover& cover,
              const RowBounds& bounds, bool inFront, bool inBack, ShownSpan& front, ShownSpan& back,
              Walk walk = Walk::Fastest);

}  // namespace spindrift::occlusion_rows
