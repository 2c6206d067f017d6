#pragma once

#include "framedata/SmoothedDepth.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/DepthPingPong.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Baseline: Green's separable bilateral filter of eye depth (GDC 2010), liquid.smoothing_iterations times an
/// x and a y pass, as Imai et al. iterate it. Pulls silhouettes towards the camera (liquid paper, Problem 2).
class BilateralFilterPass {
 public:
  explicit BilateralFilterPass(const ShaderLibrary& shaders);
  /// With no iterations the result is `eyeDepth` itself.
  SmoothedDepth run(const Texture2D& eyeDepth, float particleRadius, const LiquidParameters& parameters,
                    DepthPingPong& targets);

 private:
  ProgramObject program_;
};

}  // namespace spindrift
