#pragma once

#include <vector>

#include "framedata/DepthLayers.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/DepthSmoothingPass.h"
#include "passes/EllipsoidImpostorPass.h"
#include "passes/FrameUniforms.h"
#include "passes/PixelTilePass.h"
#include "prep/LightViews.h"

namespace spindrift {

/// The liquid as a light sees it: the front and back depth layers of its ellipsoids drawn and smoothed in the
/// light's view, by the same passes as the camera's layers (so this composes passes, like the recipe, rather
/// than being one). The light's frame block is left bound at
/// binding 2 (shaders/lib/light_view.glsl) and the camera's is restored at binding 0.
class LightDepthLayers {
 public:
  explicit LightDepthLayers(const ShaderLibrary& shaders);
  SurfaceLayers run(const LightPreparation& light, const Camera& camera, float particleRadius,
                    const LiquidParameters& parameters);
  /// The depths alone, unsmoothed and without normals (left zero), in one draw
  /// (EllipsoidImpostorPass::runDepthRange): what the sky's view needs.
  SurfaceLayers runDepthOnly(const LightPreparation& light, const Camera& camera);

 private:
  /// The light's view bound at binding 0 and its impostors drawn, with their normals.
  SurfaceLayers draw(const LightPreparation& light);
  /// The light's view to binding 2 (lib/light_view.glsl), the camera's back to binding 0.
  void restoreViews(const LightPreparation& light, const Camera& camera);

  FrameUniformBuffer lightUniforms_;
  FrameUniformBuffer cameraUniforms_;
  EllipsoidImpostorPass impostors_;
  PixelTilePass tiles_;
  DepthSmoothingPass frontSmoothing_;
  DepthSmoothingPass backSmoothing_;
};

}  // namespace spindrift
