#pragma once

#include <optional>
#include <vector>

#include "framedata/BackgroundData.h"
#include "framedata/DepthLayers.h"
#include "gl/PassTimer.h"
#include "passes/DensityMaskPass.h"
#include "passes/RaymarchEntryPass.h"
#include "passes/RaymarchGridPass.h"
#include "passes/RaymarchPass.h"
#include "passes/RaymarchTilePass.h"
#include "passes/RaymarchUpsamplePass.h"
#include "prep/RaymarchPreparation.h"
#include "spindrift/RenderResult.h"

namespace spindrift {

/// The ray-marched first surface (liquid.surface = raymarch; docs/raymarch.md): the adaptive ray marching
/// paper's algorithm 1 as six passes, each timed on its own. It replaces the front layers of the splashes and
/// aggregates; their back layers, the refraction and everything after stay as they are.
class RaymarchSurface {
 public:
  explicit RaymarchSurface(const ShaderLibrary& shaders);

  /// At least one of `splashes` and `aggregates` is present. The frame's uniform block must be current.
  MarchedFronts run(const RaymarchPreparation& preparation, const std::optional<SurfaceLayers>& splashes,
                    const std::optional<SurfaceLayers>& aggregates, const BackgroundData& background,
                    const LiquidParameters& parameters, PassTimer& timer, int width, int height);
  /// The counters and tile histogram of the last run (waits for the GPU).
  RaymarchFrameStats statistics() const;
  /// raymarch_entry_depth.Z, raymarch_sample_depth.Z (each cast ray's surface, 1e10 where it found none or
  /// none was cast), raymarch_steps.Y and raymarch_ray_spacing.Y (1, 2 or 4 pixels; 0 without liquid) of the
  /// last run, for --intermediate.
  std::vector<ImageLayer> intermediateLayers() const;
  /// The density grid of the last run unpacked to a byte per cell (for the tests).
  std::vector<std::uint8_t> densityMaskCells() const { return mask_.readCells(); }

 private:
  struct EmptyLayer {
    Texture2D eyeDepth, normal;
  };
  const DepthLayer& emptyLayer(int width, int height);

  RaymarchGridPass grid_;
  DensityMaskPass mask_;
  RaymarchEntryPass entry_;
  RaymarchTilePass tiles_;
  RaymarchPass march_;
  RaymarchUpsamplePass upsample_;
  EmptyLayer empty_;
  std::optional<DepthLayer> emptyLayer_;
  const Texture2D* lastEntryDepth_ = nullptr;
  const Texture2D* lastSteps_ = nullptr;
  const Texture2D* lastSampleDepth_ = nullptr;
  const Texture2D* lastLevels_ = nullptr;
  int lastTileSize_ = 16;
  RaymarchFrameStats lastStats_;
};

/// Puts the marched fronts in place of the impostors' front layers, keeping their back layers.
void replaceFrontLayers(const MarchedFronts& fronts, std::optional<SurfaceLayers>& splashes,
                        std::optional<SurfaceLayers>& aggregates);

}  // namespace spindrift
