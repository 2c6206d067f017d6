#include "LiquidLighting.h"

namespace spindrift {
namespace {

bool refracts(const LightPreparation& light, const Parameters& parameters) {
  return parameters.light.caustics && light.view.light.type != Light::Type::Point;
}

}  // namespace

LiquidLighting::LiquidLighting(const ShaderLibrary& shaders)
    : layers_(shaders),
      shadow_(shaders),
      skyOcclusion_(shaders),
      caustics_(shaders),
      litTiles_(shaders),
      litBackground_(shaders) {}

SurfaceLayers LiquidLighting::drawLight(const LightPreparation& light, const Camera& camera,
                                        const BackgroundData& background, float particleRadius,
                                        const Parameters& parameters, bool withShadowPass, PassTimer& timer) {
  std::optional<SurfaceLayers> layers;
  {
    ScopedPassTimer timed(timer, "light_depth_layers");
    layers.emplace(layers_.run(light, camera, particleRadius, parameters.liquid));
  }
  if (withShadowPass) {
    ScopedPassTimer timed(timer, "liquid_shadow");
    shadow_.addLight(light.view.light, *layers, background, parameters.liquid, !refracts(light, parameters));
  }
  if (refracts(light, parameters)) {
    ScopedPassTimer timed(timer, "caustics");
    caustics_.addLight(light.view.light, *layers, background, parameters.liquid, parameters.light);
  }
  return *layers;
}

LitBackgroundData LiquidLighting::run(const LightingPreparation& lights, const Camera& camera,
                                      const BackgroundData& background, float particleRadius,
                                      const Parameters& parameters, bool occludeSky, bool shadowPass,
                                      bool litTiles, PassTimer& timer) {
  const int width = camera.width, height = camera.height;
  caustics_.begin(width, height);
  // Without the shadow pass (FramePlan skips it for one light whose caustics carry what crosses the liquid,
  // beside the sky occlusion's samples) the lit background finds that light's shadow itself, one full-screen
  // pass fewer (docs/frame-cost.md, session 44). Its layers are drawn after the sky's, whose depth range
  // shares their targets, and stay bound for it.
  // The world's light alone (no lamp sees the liquid) has no shadow to find: the sums stay empty, and the
  // lit background takes its sky light alone (LitBackgroundPass, light.direct_fraction 0).
  const bool shadowInLitBackground = !shadowPass && !lights.lights.empty();
  if (!shadowInLitBackground) {
    shadow_.begin(width, height);
    for (const LightPreparation& light : lights.lights)
      drawLight(light, camera, background, particleRadius, parameters, true, timer);
  }
  // prepareLights gives the sky's view with every set of lights: the sky light a submerged point loses.
  const LightPreparation& sky = lights.sky.value();
  std::optional<SurfaceLayers> skyLayers;
  {
    ScopedPassTimer timed(timer, "sky_depth_layers");
    // Depth below the surface and the liquid a point's hemisphere holds need no normals, so the sky's layers
    // are neither smoothed nor given normals.
    skyLayers.emplace(layers_.runDepthOnly(sky, camera));
  }
  std::optional<SkyOcclusionData> occlusion;
  skyOcclusionScale_ = occludeSky ? spindrift::skyOcclusionScale(lights.bounds, camera) : 0;
  if (occludeSky) {
    ScopedPassTimer timed(timer, "sky_occlusion");
    occlusion.emplace(skyOcclusion_.run(*skyLayers, sky.view, lights.bounds, background, parameters,
                                        skyOcclusionScale_, width, height));
  }
  std::optional<SurfaceLayers> lightLayers;
  LampLight lamps;
  const LiquidShadowData sums = shadow_.result();
  if (shadowInLitBackground) {
    const LightPreparation& light = lights.lights.front();
    lightLayers.emplace(drawLight(light, camera, background, particleRadius, parameters, false, timer));
    lamps.light = &light.view.light;
    lamps.layers = &*lightLayers;
  } else {
    lamps.sums = &sums;
    lamps.none = lights.lights.empty();
  }
  std::optional<LitTiles> tiles;
  if (litTiles && occlusion) {
    ScopedPassTimer timed(timer, "lit_tiles");
    tiles.emplace(litTiles_.run(background, lamps, caustics_.result(), *occlusion, width, height));
  }
  ScopedPassTimer timed(timer, "lit_background");
  return litBackground_.run(background, lamps, caustics_.result(),
                            SkyView{*skyLayers, occlusion ? &*occlusion : nullptr, particleRadius},
                            parameters, tiles ? &*tiles : nullptr, width, height);
}

}  // namespace spindrift
