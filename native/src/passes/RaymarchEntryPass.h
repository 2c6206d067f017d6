#pragma once

#include <memory>
#include <optional>

#include "framedata/DepthLayers.h"
#include "framedata/RaymarchEntryData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// D_all from the splash and aggregate front layers (shaders/raymarch_entry.comp), smoothed by the bilateral
/// Gaussian filter (liquid.bilateral_* parameters, liquid.smoothing_iterations iterations) for N_screen.
class RaymarchEntryPass {
 public:
  explicit RaymarchEntryPass(const ShaderLibrary& shaders);
  ~RaymarchEntryPass();
  /// `emptyLayer` stands in for an absent splash or aggregate set.
  RaymarchEntryData run(const std::optional<SurfaceLayers>& splashes,
                        const std::optional<SurfaceLayers>& aggregates, const DepthLayer& emptyLayer,
                        float particleRadius, const LiquidParameters& parameters, int width, int height);

 private:
  struct Smoothing;  // the bilateral filter and normals passes it is made of (RaymarchEntryPass.cpp)
  ProgramObject program_;
  std::unique_ptr<Smoothing> smoothing_;
  Texture2D allDepth_;
  Texture2D allNormal_;
};

}  // namespace spindrift
