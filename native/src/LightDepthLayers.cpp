#include "LightDepthLayers.h"

#include <algorithm>
#include <cmath>

namespace spindrift {

LightDepthLayers::LightDepthLayers(const ShaderLibrary& shaders)
    : impostors_(shaders), tiles_(shaders), frontSmoothing_(shaders), backSmoothing_(shaders) {}

SurfaceLayers LightDepthLayers::draw(const LightPreparation& light) {
  // The impostor and smoothing shaders read the view from binding 0: give them the light's for a while.
  lightUniforms_.update(light.view.camera, 0);
  // A light's view has no background: nothing hides the liquid from it.
  return impostors_.run(light.liquid.aggregates, light.liquid.aggregateLayers, nullptr, light.view.camera,
                        nullptr);
}

void LightDepthLayers::restoreViews(const LightPreparation& light, const Camera& camera) {
  lightUniforms_.update(light.view.camera, 2);
  cameraUniforms_.update(camera, 0);
}

SurfaceLayers LightDepthLayers::runDepthOnly(const LightPreparation& light, const Camera& camera) {
  lightUniforms_.update(light.view.camera, 0);
  const SurfaceLayers drawn = impostors_.runDepthRange(light.liquid.aggregates, light.view.camera);
  restoreViews(light, camera);
  return drawn;
}

SurfaceLayers LightDepthLayers::run(const LightPreparation& light, const Camera& camera, float particleRadius,
                                    const LiquidParameters& parameters) {
  const int size = light.view.camera.width;
  const SurfaceLayers drawn = draw(light);
  if (parameters.smoothing == "none") {
    restoreViews(light, camera);
    return drawn;
  }
  // The plane-fit window smooths away the particles' bumps: a particle across (half a radius each side of the
  // centre texel, rounded), however coarse the view (light.texels_per_radius). A window fixed in texels
  // rounds the body's edges more in a coarser view and shifts its shadow
  // (GLLiquidLight.SlabShadowShiftsAsSnellsLawSays failed by 0.11 m at 207 texels with the camera's 9).
  LiquidParameters smoothing = parameters;
  smoothing.plane_fit_reference_height = 0;  // the window is sized in the view's own texels below
  if (light.view.texelSize > 0.0f) {
    const int halfWindow = int(std::lround(0.5f * particleRadius / light.view.texelSize));
    smoothing.plane_fit_window = std::clamp(2 * halfWindow + 1, 3, parameters.plane_fit_window);
  }
  // Only the texel tiles that hold liquid are smoothed, as the camera's are. The view frames the liquid's
  // bounding sphere, which a compact body fills half of or less: the light benchmark's pool holds its sun's
  // view in 61 of 121 tiles, its ball in 24 of 64 (docs/frame-cost.md, session 61).
  const PixelTiles withLiquid = tiles_.run({&drawn.front.eyeDepth, &drawn.back.eyeDepth}, size, size);
  const DepthLayer front =
      frontSmoothing_.run(drawn.front, particleRadius, false, smoothing, &withLiquid, size, size);
  const DepthLayer back =
      backSmoothing_.run(drawn.back, particleRadius, true, smoothing, &withLiquid, size, size);
  restoreViews(light, camera);
  return {front, back};
}

}  // namespace spindrift
