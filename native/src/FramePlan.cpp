#include "FramePlan.h"

#include <algorithm>

namespace spindrift {

const char* passName(Pass pass) {
  switch (pass) {
    case Pass::Background:
      return "background";
    case Pass::OccluderDepth:
      return "occluder_depth";
    case Pass::LiquidMeshDepth:
      return "liquid_mesh_depth";
    case Pass::LightDepthLayers:
      return "light_depth_layers";
    case Pass::LiquidShadow:
      return "liquid_shadow";
    case Pass::Caustics:
      return "caustics";
    case Pass::SkyOcclusion:
      return "sky_occlusion";
    case Pass::LitTiles:
      return "lit_tiles";
    case Pass::LitBackground:
      return "lit_background";
    case Pass::SplashDepthLayers:
      return "splash_depth_layers";
    case Pass::AggregateDepthLayers:
      return "aggregate_depth_layers";
    case Pass::LiquidTiles:
      return "liquid_tiles";
    case Pass::Smoothing:
      return "smoothing";
    case Pass::RimNormals:
      return "rim_normals";
    case Pass::RaymarchSurface:
      return "raymarch_surface";
    case Pass::Refraction:
      return "refraction";
    case Pass::RefractionFootprint:
      return "refraction_footprint";
    case Pass::FoamSceneDepth:
      return "foam_scene_depth";
    case Pass::FoamVisibility:
      return "foam_visibility";
    case Pass::FoamDepth:
      return "foam_depth";
    case Pass::FoamThickness:
      return "foam_thickness";
    case Pass::FoamIntensity:
      return "foam_intensity";
    case Pass::FoamTiles:
      return "foam_tiles";
    case Pass::FoamOcclusion:
      return "foam_occlusion";
    case Pass::FoamBlur:
      return "foam_blur";
    case Pass::Composite:
      return "composite";
  }
  return "unknown";
}

bool FramePlan::runs(Pass pass) const {
  return std::find(passes.begin(), passes.end(), pass) != passes.end();
}

FramePlan planFrame(const FrameContents& contents) {
  FramePlan plan;
  // A pass runs when `reason` is empty; otherwise it is listed as skipped with that reason.
  auto decide = [&plan](Pass pass, const char* reason) {
    if (reason)
      plan.skipped.push_back({passName(pass), reason});
    else
      plan.passes.push_back(pass);
  };
  const bool splashes = contents.splashParticles > 0;
  const bool aggregates = contents.aggregateParticles > 0;
  const bool foamShown = contents.compositeWanted || contents.foamLayersWanted;
  const bool foamRuns = contents.foamParticles > 0 && foamShown;
  // The foam reads the liquid's first surface, so foam that is drawn needs the liquid too.
  const bool liquidShown = contents.compositeWanted || contents.liquidLayersWanted || foamRuns;
  const bool layersShown = liquidShown || contents.intermediateWanted;
  const char* noLiquidOutput = "no liquid layer, composite or foam asked for (--layers)";
  decide(Pass::Background, nullptr);
  decide(Pass::OccluderDepth, contents.occluderMeshes > 0 ? nullptr : "no occluders");
  decide(Pass::LiquidMeshDepth, contents.liquidMesh ? nullptr : "no liquid mesh");
  // Light through the liquid onto the background: for every light that sees the liquid (LiquidLighting).
  // The lit background reaches the refraction and the composite, and the light layers themselves.
  const bool lightShown = liquidShown || contents.lightLayersWanted;
  const char* notShown =
      !lightShown ? "no light layer, liquid layer, composite or foam asked for (--layers)" : nullptr;
  const char* noLamp = contents.lights == 0               ? "no lights in the scene"
                       : contents.lightsSeeingLiquid == 0 ? "no light sees the liquid"
                                                          : notShown;
  // Without a lamp the world's light may still light the background: the sky's passes and the lit
  // background run, the lamps' own passes do not (docs/liquid.md, "The world's light alone").
  const char* noLight = contents.worldLightsAlone && !notShown ? nullptr : noLamp;
  const char* noCaustics = noLamp                        ? noLamp
                           : !contents.caustics          ? "light.caustics is off"
                           : contents.causticLights == 0 ? "no sun or spot light sees the liquid"
                                                         : nullptr;
  const char* noSkyOcclusion = noLight                                ? noLight
                               : contents.skyOcclusionDirections == 0 ? "light.sky_occlusion_directions is 0"
                                                                      : nullptr;
  // One light, whose caustics carry what crosses the liquid, beside the sky occlusion's samples: the lit
  // background finds its shadow itself (lib/liquid_shadow.glsl), and its layers and caustics come after the
  // sky's passes, whose depth range shares their targets (LiquidLighting).
  if (!noCaustics && !noSkyOcclusion && contents.lightsSeeingLiquid == 1) {
    decide(Pass::SkyOcclusion, nullptr);
    decide(Pass::LightDepthLayers, nullptr);
    decide(Pass::LiquidShadow, "the lit background finds the one light's shadow itself");
    decide(Pass::Caustics, nullptr);
  } else {
    for (Pass pass : {Pass::LightDepthLayers, Pass::LiquidShadow})
      decide(pass, noLamp);
    decide(Pass::Caustics, noCaustics);
    decide(Pass::SkyOcclusion, noSkyOcclusion);
  }
  // The sky occlusion's samples say where the liquid takes sky light; without them every pixel is lit.
  decide(Pass::LitTiles, noSkyOcclusion             ? noSkyOcclusion
                         : !contents.skipUnlitTiles ? "light.skip_unlit_tiles is off"
                                                    : nullptr);
  decide(Pass::LitBackground, noLight);
  decide(Pass::SplashDepthLayers, !splashes      ? "no splash particles in view"
                                  : !layersShown ? noLiquidOutput
                                                 : nullptr);
  decide(Pass::AggregateDepthLayers, !aggregates    ? "no aggregate particles in view"
                                     : !layersShown ? noLiquidOutput
                                                    : nullptr);
  decide(Pass::LiquidTiles, !(splashes || aggregates)  ? "no liquid particles in view"
                            : !layersShown             ? noLiquidOutput
                            : !contents.skipEmptyTiles ? "liquid.skip_empty_tiles is off"
                                                       : nullptr);
  decide(Pass::Smoothing, !aggregates                    ? "no aggregate particles in view"
                          : contents.smoothing == "none" ? "liquid.smoothing is none"
                          : !layersShown                 ? noLiquidOutput
                                                         : nullptr);
  decide(Pass::RimNormals, !aggregates            ? "no aggregate particles in view"
                           : !contents.rimNormals ? "liquid.rim_normals is off"
                           : contents.surface == "raymarch"
                               ? "the ray-marched surface replaces the front layer"
                           : contents.cameraInLiquid ? "the camera is under water: no front layer is drawn"
                           : !layersShown            ? noLiquidOutput
                                                     : nullptr);
  // The ray-marched surface is part of the frame only where liquid.surface asks for it: a screen-space frame
  // does not list it as skipped.
  if (contents.surface == "raymarch")
    decide(Pass::RaymarchSurface, !(splashes || aggregates) ? "no liquid particles in view"
                                  : !layersShown            ? noLiquidOutput
                                                            : nullptr);
  const char* noRefraction = !(splashes || aggregates) ? "no liquid particles in view"
                             : !liquidShown            ? noLiquidOutput
                                                       : nullptr;
  decide(Pass::Refraction, noRefraction);
  decide(Pass::RefractionFootprint, noRefraction                     ? noRefraction
                                    : contents.pixelFilterWidth <= 0 ? "liquid.pixel_filter_width is 0"
                                                                     : nullptr);
  const char* foamReason = contents.foamParticles == 0 ? "no foam particles in view"
                           : !foamShown                ? "no foam layer or composite asked for (--layers)"
                                                       : nullptr;
  decide(Pass::FoamSceneDepth, foamReason);
  decide(Pass::FoamVisibility, foamReason             ? foamReason
                               : contents.foamCulling ? nullptr
                                                      : "foam.cull_hidden is off");
  for (Pass pass : {Pass::FoamDepth, Pass::FoamThickness, Pass::FoamIntensity})
    decide(pass, foamReason);
  decide(Pass::FoamTiles, foamReason                     ? foamReason
                          : !contents.skipEmptyFoamTiles ? "foam.skip_empty_tiles is off"
                                                         : nullptr);
  for (Pass pass : {Pass::FoamOcclusion, Pass::FoamBlur})
    decide(pass, foamReason);
  decide(Pass::Composite, contents.compositeWanted ? nullptr : "composite not asked for (--layers)");
  return plan;
}

}  // namespace spindrift
