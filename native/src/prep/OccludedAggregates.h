#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "prep/LiquidPreparation.h"
#include "prep/SolidDepthTiles.h"
#include "spindrift/Camera.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// What dropOccludedAggregates did to one view's ellipsoids.
struct OccludedAggregatesResult {
  std::size_t hiddenFromFront = 0;  ///< Newly left out of the front layer (including those dropped).
  std::size_t hiddenFromBack = 0;   ///< Newly left out of the back layer (including those dropped).
  std::size_t dropped = 0;          ///< Now in neither layer: left out.
  /// Over the ellipsoids left in each layer (once per layer): the pixels of their rectangles where the
  /// impostor pass may draw them (the grown ellipsoid's, clamped to the view), and of their shown rectangles,
  /// to which the impostor pass limits them.
  std::uint64_t reachPixels = 0;
  std::uint64_t shownPixels = 0;
  double milliseconds = 0.0;
};

/// Memory dropOccludedAggregates keeps from one call to the next: its per-ellipsoid views (248 bytes each),
/// which a sequence's frames then write into pages already mapped. Allocated afresh, the bigger bake's 36 MB
/// (150,000 particles) were faulted in again every frame: 8,900 page faults, about 30 ms of CPU time
/// (docs/frame-cost.md, session 43). One workspace serves one call at a time.
class OcclusionWorkspace {
 public:
  OcclusionWorkspace();
  ~OcclusionWorkspace();
  OcclusionWorkspace(OcclusionWorkspace&&) noexcept;
  OcclusionWorkspace& operator=(OcclusionWorkspace&&) noexcept;
  /// Ellipsoids' room held (for tests).
  std::size_t capacity() const;

  struct Views;  // OccludedAggregates.cpp

 private:
  friend OccludedAggregatesResult dropOccludedAggregates(std::vector<EllipsoidInstance>&, LayerSplit&,
                                                         const Camera&, const DomainBox*,
                                                         const SolidDepthTiles*, OcclusionWorkspace*);
  std::unique_ptr<Views> views_;
};

/// Leaves out of each depth layer the ellipsoids that another one hides from the view at every pixel they
/// could cover, on the view's own pixel grid. An ellipsoid Q covers a pixel when the pixel's ray passes
/// through Q's inscribed ball: there the front layer is at most Q's farthest depth (its bounding sphere's).
/// An ellipsoid P whose nearest depth lies beyond that at every pixel its bounding sphere may reach never
/// wins a front pixel; the back layer likewise, mirrored. Unlike dropHiddenInterior this needs no overlap
/// between the particles (a lattice of spheres has gaps between them that the view never sees through) and
/// it also drops what a nearer part of the body hides (a wave's back behind its front).
///
/// Q counts as covering only where its fragments are certain to be drawn: whole inside the near and far
/// planes and, for the back layer, with no solid nearer than its farthest depth (the impostor pass hides an
/// ellipsoid whose entry lies behind a solid). Where a domain box cuts Q, its chord is clipped to the box as
/// the impostor pass clips it, and Q covers the pixels where some of it is left: liquid resting on a domain's
/// floor or walls is mostly such ellipsoids (30,270 of the 37,070 drawn into the dam break's front layer).
/// Where the background's depth puts a solid at or before an ellipsoid's nearest depth, the impostor pass
/// hides it at that pixel in both layers: one hidden so at every pixel it may reach is dropped (the dam
/// break's grazing camera, whose obstacle and walls hide most of the water: 11,654 → 51,943 dropped).
/// `ellipsoids` and `split` come as dropHiddenInterior leaves them ([front only | both | back only]) and
/// leave in that order too. `workspace` (may be null) lends the memory of an earlier call.
OccludedAggregatesResult dropOccludedAggregates(std::vector<EllipsoidInstance>& ellipsoids, LayerSplit& split,
                                                const Camera& camera, const DomainBox* domain,
                                                const SolidDepthTiles* solids,
                                                OcclusionWorkspace* workspace = nullptr);

}  // namespace spindrift
