#include "LiquidLighting.h"

namespace spindrift {

LiquidLighting::LiquidLighting(const ShaderLibrary& shaders)
    : layers_(shaders),
      shadow_(shaders),
      skyOcclusion_(shaders),
      caustics_(shaders),
      litBackground_(shaders) {}

LitBackgroundData LiquidLighting::run(const LightingPreparation& lights, const Camera& camera,
                                      const BackgroundData& background, float particleRadius,
                                      const Parameters& parameters, bool occludeSky, PassTimer& timer) {
  const int width = camera.width, height = camera.height;
  shadow_.begin(width, height);
  caustics_.begin(width, height);
  for (const LightPreparation& light : lights.lights) {
    const bool refracts = parameters.light.caustics && light.view.light.type != Light::Type::Point;
    std::optional<SurfaceLayers> layers;
    {
      ScopedPassTimer timed(timer, "light_depth_layers");
      layers.emplace(layers_.run(light, camera, particleRadius, parameters.liquid));
    }
    {
      ScopedPassTimer timed(timer, "liquid_shadow");
      shadow_.addLight(light.view.light, *layers, background, parameters.liquid, !refracts);
    }
    if (refracts) {
      ScopedPassTimer timed(timer, "caustics");
      caustics_.addLight(light.view.light, *layers, background, parameters.liquid, parameters.light);
    }
  }
  // prepareLights gives the sky's view with every set of lights: the sky light a submerged point loses.
  const LightPreparation& sky = lights.sky.value();
  std::optional<SurfaceLayers> layers;
  {
    ScopedPassTimer timed(timer, "sky_depth_layers");
    // Depth below the surface and the liquid a point's hemisphere holds need no normals, so the sky's layers
    // are neither smoothed nor given normals.
    layers.emplace(layers_.runDepthOnly(sky, camera));
  }
  std::optional<SkyOcclusionData> occlusion;
  if (occludeSky) {
    ScopedPassTimer timed(timer, "sky_occlusion");
    occlusion.emplace(
        skyOcclusion_.run(*layers, sky.view, lights.bounds, background, parameters, width, height));
  }
  ScopedPassTimer timed(timer, "lit_background");
  return litBackground_.run(background, shadow_.result(), caustics_.result(),
                            SkyView{*layers, occlusion ? &*occlusion : nullptr, particleRadius}, parameters,
                            width, height);
}

}  // namespace spindrift
