#pragma once

#include <memory>

#include "framedata/DepthLayers.h"
#include "framedata/PixelTiles.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Smooths an aggregate depth layer with the method liquid.smoothing names (plane_fit, bilateral,
/// curvature_flow, narrow_range or none) and recomputes its normals from the smoothed depth. Empty pixels
/// stay empty: smoothing never creates a surface. The frame's uniform block (binding 0) must be current. The
/// result lives in the pass's own textures until its next run, so a frame uses one instance per layer.
class DepthSmoothingPass {
 public:
  explicit DepthSmoothingPass(const ShaderLibrary& shaders);
  ~DepthSmoothingPass();

  /// `particleRadius` is the liquid's world radius r, which the methods' parameters are scaled by.
  /// `backLayer` says the layer's outward normals face away from the camera. With `tiles` (which must mark
  /// every tile where the layer has a surface) only those tiles are shaded; the rest hold the empty values.
  DepthLayer run(const DepthLayer& layer, float particleRadius, bool backLayer,
                 const LiquidParameters& parameters, const PixelTiles* tiles, int width, int height);

 private:
  struct Methods;
  std::unique_ptr<Methods> methods_;
};

}  // namespace spindrift
