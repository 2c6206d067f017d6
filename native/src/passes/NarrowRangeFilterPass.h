#pragma once

#include "framedata/SmoothedDepth.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/DepthPingPong.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Baseline: Truong and Yuksel's narrow-range filter (i3D 2018) in its 1D separable form,
/// liquid.smoothing_iterations times an x and a y pass.
class NarrowRangeFilterPass {
 public:
  explicit NarrowRangeFilterPass(const ShaderLibrary& shaders);
  /// With no iterations the result is `eyeDepth` itself.
  SmoothedDepth run(const Texture2D& eyeDepth, float particleRadius, const LiquidParameters& parameters,
                    DepthPingPong& targets);

 private:
  ProgramObject program_;
};

}  // namespace spindrift
