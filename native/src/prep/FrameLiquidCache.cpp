#include "prep/FrameLiquidCache.h"

namespace spindrift {

FrameLiquidCache& LiquidCacheAcrossFrames::forFrame(const Particles& particles,
                                                    const LiquidParameters& parameters) {
  if (!parameters.reuse_shapes)
    whyNotKept_ = "liquid.reuse_shapes is false";
  else if (!filled_)
    whyNotKept_ = "no frame before it kept them";
  else if (!(parameters == parameters_))
    whyNotKept_ = "the liquid parameters changed";
  else if (particles.positions != positions_ || particles.radii != radii_ || particles.kinds != kinds_)
    whyNotKept_ = "the particles changed";
  else
    whyNotKept_.clear();
  if (whyNotKept_.empty()) return cache_;
  cache_.clear();
  filled_ = parameters.reuse_shapes;
  if (filled_) {
    positions_ = particles.positions;
    radii_ = particles.radii;
    kinds_ = particles.kinds;
    parameters_ = parameters;
  }
  return cache_;
}

}  // namespace spindrift
