#include "LightDepthLayers.h"

#include <algorithm>
#include <cmath>

namespace spindrift {

LightDepthLayers::LightDepthLayers(const ShaderLibrary& shaders)
    : impostors_(shaders), frontSmoothing_(shaders), backSmoothing_(shaders) {}

SurfaceLayers LightDepthLayers::run(const LightPreparation& light, const Camera& camera, float particleRadius,
                                    const LiquidParameters& parameters) {
  const int size = light.view.camera.width;
  if (!noSolids_.matches(size, size, GL_R32F)) {
    ensureTexture(noSolids_, GL_R32F, size, size);
    const float farAway = 1e10f;
    glClearTexImage(noSolids_.id(), 0, GL_RED, GL_FLOAT, &farAway);
  }
  // The impostor and smoothing shaders read the view from binding 0: give them the light's for a while.
  lightUniforms_.update(light.view.camera, 0);
  const BackgroundData noBackground{noSolids_, noSolids_, nullptr, glm::vec3(0.0f), nullptr};
  const SurfaceLayers drawn =
      impostors_.run(light.liquid.aggregates, light.liquid.aggregateLayers, noBackground, light.view.camera);
  const auto restoreViews = [&] {
    lightUniforms_.update(light.view.camera, 2);
    cameraUniforms_.update(camera, 0);
  };
  if (parameters.smoothing == "none") {
    restoreViews();
    return drawn;
  }
  // The plane-fit window smooths away the particles' bumps: a particle across (half a radius each side of the
  // centre texel, rounded), however coarse the view (light.texels_per_radius). A window fixed in texels
  // rounds the body's edges more in a coarser view and shifts its shadow
  // (GLLiquidLight.SlabShadowShiftsAsSnellsLawSays failed by 0.11 m at 207 texels with the camera's 9).
  LiquidParameters smoothing = parameters;
  if (light.view.texelSize > 0.0f) {
    const int halfWindow = int(std::lround(0.5f * particleRadius / light.view.texelSize));
    smoothing.plane_fit_window = std::clamp(2 * halfWindow + 1, 3, parameters.plane_fit_window);
  }
  const DepthLayer front = frontSmoothing_.run(drawn.front, particleRadius, false, smoothing, size, size);
  const DepthLayer back = backSmoothing_.run(drawn.back, particleRadius, true, smoothing, size, size);
  restoreViews();
  return {front, back};
}

}  // namespace spindrift
