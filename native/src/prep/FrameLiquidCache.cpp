#include "prep/FrameLiquidCache.h"

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
                                                "liquid.mesh_kernel_radius",
                                                "liquid.reuse_shapes"};
  return keys;
}

bool sameShapingParameters(const LiquidParameters& a, const LiquidParameters& b) {
  return a.layers == b.layers && a.neighbour_radius == b.neighbour_radius &&
         a.anisotropy_max_ratio == b.anisotropy_max_ratio &&
         a.anisotropy_min_neighbours == b.anisotropy_min_neighbours &&
         a.anisotropy_min_neighbour_fraction == b.anisotropy_min_neighbour_fraction &&
         a.anisotropy_isotropic_scale == b.anisotropy_isotropic_scale &&
         a.anisotropy_smoothing == b.anisotropy_smoothing && a.max_ellipsoid_scale == b.max_ellipsoid_scale &&
         a.surface_offset == b.surface_offset && a.reach_radius == b.reach_radius &&
         a.mesh_kernel_radius == b.mesh_kernel_radius && a.reuse_shapes == b.reuse_shapes;
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
