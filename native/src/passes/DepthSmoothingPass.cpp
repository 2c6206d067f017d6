#include "passes/DepthSmoothingPass.h"

#include "passes/BilateralFilterPass.h"
#include "passes/CurvatureFlowPass.h"
#include "passes/DepthPingPong.h"
#include "passes/NarrowRangeFilterPass.h"
#include "passes/NormalsFromDepthPass.h"
#include "passes/PlaneFitPass.h"
#include "spindrift/Error.h"

namespace spindrift {

// Every method's program is compiled up front, so switching liquid.smoothing between frames costs nothing
// and a broken shader fails when the renderer starts, not in the middle of a sequence.
struct DepthSmoothingPass::Methods {
  explicit Methods(const ShaderLibrary& shaders)
      : planeFit(shaders),
        bilateral(shaders),
        curvatureFlow(shaders),
        narrowRange(shaders),
        normals(shaders) {}

  PlaneFitPass planeFit;
  BilateralFilterPass bilateral;
  CurvatureFlowPass curvatureFlow;
  NarrowRangeFilterPass narrowRange;
  NormalsFromDepthPass normals;
  DepthPingPong depthTargets;
  Texture2D passedThroughNormal;  // `none` keeps the layer's normals, copied so the result is the pass's own
};

DepthSmoothingPass::DepthSmoothingPass(const ShaderLibrary& shaders)
    : methods_(std::make_unique<Methods>(shaders)) {}

DepthSmoothingPass::~DepthSmoothingPass() = default;

DepthLayer DepthSmoothingPass::run(const DepthLayer& layer, float particleRadius, bool backLayer,
                                   const LiquidParameters& parameters, const PixelTiles* tiles, int width,
                                   int height) {
  Methods& methods = *methods_;
  DepthPingPong& targets = methods.depthTargets;
  targets.prepare(width, height, tiles);
  const std::string& method = parameters.smoothing;
  if (method == "none") {
    Texture2D& normal = methods.passedThroughNormal;
    ensureTexture(normal, layer.normal.internalFormat, width, height);
    glCopyImageSubData(layer.normal.id(), GL_TEXTURE_2D, 0, 0, 0, 0, normal.id(), GL_TEXTURE_2D, 0, 0, 0, 0,
                       width, height, 1);
    checkGlError("copying a depth layer's normals");
    return {targets.copy(layer.eyeDepth), normal};
  }

  const Texture2D* smoothed = nullptr;
  if (method == "plane_fit")
    smoothed =
        &methods.planeFit.run(layer.eyeDepth, layer.normal, particleRadius, parameters, targets).eyeDepth;
  else if (method == "bilateral")
    smoothed = &methods.bilateral.run(layer.eyeDepth, particleRadius, parameters, targets).eyeDepth;
  else if (method == "curvature_flow")
    smoothed = &methods.curvatureFlow.run(layer.eyeDepth, parameters, targets).eyeDepth;
  else if (method == "narrow_range")
    smoothed = &methods.narrowRange.run(layer.eyeDepth, particleRadius, parameters, targets).eyeDepth;
  else
    throw Error("liquid.smoothing: unknown method \"" + method + "\"");
  // Zero iterations leave the input's own texture; the result must live in this pass's textures.
  if (smoothed->id() == layer.eyeDepth.id()) smoothed = &targets.copy(layer.eyeDepth);
  return {*smoothed, methods.normals.run(*smoothed, layer.normal, backLayer, tiles, width, height).normal};
}

}  // namespace spindrift
