#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "prep/Anisotropy.h"
#include "prep/FullNeighbourhood.h"
#include "prep/MantaflowSurface.h"
#include "spindrift/Parameters.h"
#include "spindrift/Particles.h"

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

  /// Forgets everything, as a new cache.
  void clear() {
    search.reset();
    cellSize = 0.0f;
    shapes.reset(0);
    neighbourhood.reset();
  }
};

/// The liquid parameters ("liquid.layers", ...) that what a FrameLiquidCache keeps depends on: each
/// particle's shape and density, the frame's neighbourhood, Mantaflow's surface. The others (the smoothing,
/// the refraction, the absorption, the splash threshold, ...) change only what a view makes from it.
const std::vector<std::string>& shapingParameterKeys();
/// Whether every parameter of shapingParameterKeys() is the same in both.
bool sameShapingParameters(const LiquidParameters& a, const LiquidParameters& b);

/// A FrameLiquidCache kept from one frame to the next while everything it was computed from is unchanged: the
/// same particles bit for bit (positions, radii, kinds) and the same shaping parameters (an artist tuning
/// the water's colour or the smoothing keeps them). That is a camera
/// moving over a paused frame, as the add-on's viewport redraws it, or the cameras of one frame rendered one
/// after another: their particles are shaped once (liquid.reuse_shapes; docs/frame-cost.md). Any change
/// forgets it, so a frame's result is the same with or without it. A frame keeps its shapes only where its
/// views share them anyway (lights) or its particles are the frame before's: a one-frame process, or a
/// sequence of new particles, does not pay for keeping what no frame reuses.
class LiquidCacheAcrossFrames {
 public:
  /// The cache a frame of `particles` prepared with `parameters` fills or reuses, or null where it need not
  /// keep one. `otherViews`: the frame has views besides the camera's (lights), which share it anyway.
  FrameLiquidCache* forFrame(const Particles& particles, const LiquidParameters& parameters, bool otherViews);
  /// Empty where forFrame kept the previous frame's cache; else why it did not, for the frame's stats.
  const std::string& whyNotKept() const { return whyNotKept_; }
  /// Whether forFrame's particles and shaping parameters were the frame before's (and liquid.reuse_shapes
  /// set).
  bool sameAsBefore() const { return same_; }

 private:
  FrameLiquidCache cache_;
  bool same_ = false;
  bool keyed_ = false;   // the particles and parameters below are the last frame's
  bool filled_ = false;  // cache_ holds what the last frame's views computed
  std::vector<glm::vec3> positions_;
  std::vector<float> radii_;
  std::vector<ParticleKind> kinds_;
  LiquidParameters parameters_;
  std::string whyNotKept_;
};

}  // namespace spindrift
