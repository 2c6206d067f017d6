#pragma once

#include <optional>

#include "prep/Anisotropy.h"
#include "prep/FullNeighbourhood.h"
#include "prep/MantaflowSurface.h"

namespace spindrift {

/// What the liquid's views of one frame (the camera's, every light's, the sky's) share, so that each is
/// computed once per frame. The first view whose candidates are every liquid particle of the frame (every
/// light's view frames the whole liquid; the camera's when nothing is culled) fills it; each later such view,
/// which sorts the same particles into the same cloud, uses it. A view that culls particles uses only
/// `fullNeighbours`: its cloud differs. The result of each view is the same with or without the cache.
struct FrameLiquidCache {
  /// Mantaflow's surface over the whole liquid and its remembered searches (liquid.mesh_kernel_radius > 0).
  std::optional<MantaflowSurfaceSearch> search;
  float cellSize = 0.0f;  ///< The neighbour grid's cell size the shared cloud was sorted with; 0 before.
  ShapeMemory shapes;     ///< Each particle's shape from its neighbours, indexed like the shared cloud.
  /// frameNeighbourhood of the frame's particles, which depends on them alone.
  std::optional<FrameNeighbourhood> neighbourhood;
};

}  // namespace spindrift
