#pragma once

#include "framedata/SmoothedDepth.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/DepthPingPong.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Baseline: van der Laan et al.'s screen-space mean curvature flow (I3D 2009), liquid.curvature_flow_steps
/// explicit Euler steps of liquid.curvature_flow_time_step.
class CurvatureFlowPass {
 public:
  explicit CurvatureFlowPass(const ShaderLibrary& shaders);
  /// With no steps the result is `eyeDepth` itself.
  SmoothedDepth run(const Texture2D& eyeDepth, const LiquidParameters& parameters, DepthPingPong& targets);

 private:
  ProgramObject program_;
};

}  // namespace spindrift
