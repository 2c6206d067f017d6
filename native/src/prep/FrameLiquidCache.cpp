#include "prep/FrameLiquidCache.h"

namespace spindrift {

FrameLiquidCache* LiquidCacheAcrossFrames::forFrame(const Particles& particles,
                                                    const LiquidParameters& parameters, bool otherViews) {
  if (!parameters.reuse_shapes) {
    whyNotKept_ = "liquid.reuse_shapes is false";
    keyed_ = filled_ = same_ = false;
    cache_.clear();
    return otherViews ? &cache_ : nullptr;
  }
  const bool sameParameters = keyed_ && parameters == parameters_;
  const bool same = sameParameters && particles.positions == positions_ && particles.radii == radii_ &&
                    particles.kinds == kinds_;
  same_ = same;
  if (same && filled_) {
    whyNotKept_.clear();
    return &cache_;
  }
  whyNotKept_ = !keyed_           ? "no frame before"
                : !sameParameters ? "the liquid parameters changed"
                : !same           ? "the particles changed"
                                  : "the frame before kept none (the same particles: this frame keeps them)";
  cache_.clear();
  if (!same) {
    positions_ = particles.positions;
    radii_ = particles.radii;
    kinds_ = particles.kinds;
    parameters_ = parameters;
    keyed_ = true;
  }
  filled_ = same || otherViews;
  return filled_ ? &cache_ : nullptr;
}

}  // namespace spindrift
