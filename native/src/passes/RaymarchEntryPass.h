#pragma once

#include <optional>

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/BilateralFilterPass.h"
#include "passes/DepthPingPong.h"
#include "passes/EllipsoidImpostorPass.h"
#include "passes/NormalsFromDepthPass.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Where the rays enter, and the screen-space normal N_screen of the adaptive ray marching paper (4.4).
struct RaymarchEntryData {
  const Texture2D& allDepth;      ///< R32F D_all: the nearest front surface of every particle.
  const Texture2D& screenNormal;  ///< RGBA16F: normals of the bilateral-smoothed D_all, coverage in w.
};

/// D_all from the splash and aggregate front layers (shaders/raymarch_entry.comp), smoothed by the bilateral
/// Gaussian filter (liquid.bilateral_* parameters, liquid.smoothing_iterations iterations) for N_screen.
class RaymarchEntryPass {
 public:
  explicit RaymarchEntryPass(const ShaderLibrary& shaders);
  /// `emptyLayer` stands in for an absent splash or aggregate set.
  RaymarchEntryData run(const std::optional<SurfaceLayers>& splashes,
                        const std::optional<SurfaceLayers>& aggregates, const DepthLayer& emptyLayer,
                        float particleRadius, const LiquidParameters& parameters, int width, int height);

 private:
  ProgramObject program_;
  BilateralFilterPass bilateral_;
  NormalsFromDepthPass normals_;
  DepthPingPong smoothingTargets_;
  Texture2D allDepth_;
  Texture2D allNormal_;
};

}  // namespace spindrift
