#pragma once

#include <memory>
#include <optional>

#include "framedata/DepthLayers.h"
#include "framedata/RaymarchEntryData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"

namespace spindrift {

class DepthSmoothingPass;  // D_all is smoothed as the aggregate layers are (RaymarchEntryPass.cpp)

/// D_all from the splash and aggregate front layers (shaders/raymarch_entry.comp), smoothed by the method
/// liquid.smoothing names (the paper's bilateral Gaussian filter with `bilateral`) for N_screen.
class RaymarchEntryPass {
 public:
  explicit RaymarchEntryPass(const ShaderLibrary& shaders);
  ~RaymarchEntryPass();
  /// `emptyLayer` stands in for an absent splash or aggregate set.
  RaymarchEntryData run(const std::optional<SurfaceLayers>& splashes,
                        const std::optional<SurfaceLayers>& aggregates, const DepthLayer& emptyLayer,
                        float particleRadius, const LiquidParameters& parameters, int width, int height);

 private:
  ProgramObject program_;
  std::unique_ptr<DepthSmoothingPass> smoothing_;
  Texture2D allDepth_;
  Texture2D allNormal_;
};

}  // namespace spindrift
