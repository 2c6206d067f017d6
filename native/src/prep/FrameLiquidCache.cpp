#include "prep/FrameLiquidCache.h"

#include <algorithm>

namespace spindrift {

const std::vector<std::string>& shapingParameterKeys() {
  static const std::vector<std::string> keys = {"liquid.layers",
                                                "liquid.neighbour_radius",
                                                "liquid.anisotropy_max_ratio",
                                                "liquid.anisotropy_min_neighbours",
                                                "liquid.anisotropy_min_neighbour_fraction",
                                                "liquid.anisotropy_isotropic_scale",
                                                "liquid.anisotropy_smoothing",
                                                "liquid.max_ellipsoid_scale",
                                                "liquid.surface_offset",
                                                "liquid.reach_radius",
                                                "liquid.relax_surface",
                                                "liquid.mesh_kernel_radius",
                                                "liquid.reuse_shapes"};
  return keys;
}

bool sameShapingParameters(const LiquidParameters& a, const LiquidParameters& b) {
  // Compared through the parameter table, so that the list above is the only one.
  Parameters first, second;
  first.liquid = a;
  second.liquid = b;
  return std::all_of(
      shapingParameterKeys().begin(), shapingParameterKeys().end(),
      [&](const std::string& key) { return getParameter(first, key) == getParameter(second, key); });
}

FrameLiquidCache* LiquidCacheAcrossFrames::forFrame(const Particles& particles,
                                                    const LiquidParameters& parameters, bool otherViews) {
  if (!parameters.reuse_shapes) {
    whyNotKept_ = "liquid.reuse_shapes is false";
    keyed_ = filled_ = same_ = false;
    cache_.clear();
    return otherViews ? &cache_ : nullptr;
  }
  const bool sameParameters = keyed_ && sameShapingParameters(parameters, parameters_);
  const bool same = sameParameters && particles.positions == positions_ && particles.radii == radii_ &&
                    particles.kinds == kinds_;
  same_ = same;
  if (same && filled_) {
    whyNotKept_.clear();
    return &cache_;
  }
  whyNotKept_ = !keyed_           ? "no frame before"
                : !sameParameters ? "a shaping parameter changed"
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
