#pragma once

#include <array>
#include <map>
#include <utility>

#include "framedata/SmoothedDepth.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/DepthPingPong.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// The pixels between two of the plane fit's taps in an image `imageHeight` tall: the image's height over
/// liquid.plane_fit_reference_height, rounded, at least 1 (1 when that parameter is 0). The window keeps its
/// taps and its share of the image, so a frame rendered larger is smoothed as its preview was; a window fixed
/// in pixels smooths a surface less the more pixels its particles cover (docs/liquid.md).
int planeFitTapSpacing(int imageHeight, const LiquidParameters& parameters);

/// The liquid paper's depth smoothing (section 4.3): liquid.smoothing_iterations rounds of local plane
/// fitting in a liquid.plane_fit_window window with view-dependent weights, each round reading the previous
/// round's depth and the layer's original normals. Unlike filters, it leaves silhouettes where they are.
/// Between rounds each pixel's depth travels with its original normal in one RGBA32F texture, so that a
/// round reads each tap once.
class PlaneFitPass {
 public:
  explicit PlaneFitPass(const ShaderLibrary& shaders);
  /// `originalNormal` holds the layer's world normals before smoothing. With no iterations the result is
  /// `eyeDepth` itself.
  SmoothedDepth run(const Texture2D& eyeDepth, const Texture2D& originalNormal, float particleRadius,
                    const LiquidParameters& parameters, DepthPingPong& targets);

 private:
  /// The program of a round in a window 2 halfWindow + 1 taps wide that reads packed depth and normals and
  /// writes them packed (or depth alone), built at its first use.
  GLuint program(int halfWindow, bool packedOutput);

  const ShaderLibrary& shaders_;
  std::map<std::pair<int, bool>, ProgramObject> programs_;
  ProgramObject packProgram_;        // packs the layer's depth and normals for the first round
  std::array<Texture2D, 2> packed_;  // RGBA32F: the original normal in xyz, a round's depth in w
  FramebufferObject clearFramebuffer_;
};

}  // namespace spindrift
