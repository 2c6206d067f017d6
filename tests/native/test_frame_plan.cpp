// The frame's wiring (FramePlan.cpp), checked without a GPU: which passes run for which scene contents, in
// which order, and the reason given for each pass left out.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

#include "FramePlan.h"

namespace spindrift {
namespace {

std::vector<std::string> names(const std::vector<Pass>& passes) {
  std::vector<std::string> result;
  for (Pass pass : passes)
    result.push_back(passName(pass));
  return result;
}

std::string reasonFor(const FramePlan& plan, const std::string& pass) {
  for (const SkippedPass& skipped : plan.skipped)
    if (skipped.name == pass) return skipped.reason;
  return "";
}

const std::vector<std::string> kFoamPasses = {"foam_scene_depth", "foam_visibility", "foam_depth",
                                              "foam_thickness",   "foam_intensity",  "foam_tiles",
                                              "foam_occlusion",   "foam_blur"};

const std::vector<std::string> kLightPasses = {"light_depth_layers", "liquid_shadow", "caustics",
                                               "sky_occlusion",      "lit_tiles",     "lit_background"};

TEST(FramePlan, FullFrameRunsEveryPassInRecipeOrder) {
  FrameContents contents{100, 1000, 50, "plane_fit"};
  contents.occluderMeshes = 2;
  contents.liquidMesh = true;
  contents.lights = 2;
  contents.lightsSeeingLiquid = 2;
  contents.causticLights = 1;
  contents.caustics = true;
  const FramePlan plan = planFrame(contents);
  const std::vector<std::string> expected = {"background",
                                             "occluder_depth",
                                             "liquid_mesh_depth",
                                             "light_depth_layers",
                                             "liquid_shadow",
                                             "caustics",
                                             "sky_occlusion",
                                             "lit_tiles",
                                             "lit_background",
                                             "splash_depth_layers",
                                             "aggregate_depth_layers",
                                             "liquid_tiles",
                                             "smoothing",
                                             "rim_normals",
                                             "refraction",
                                             "refraction_footprint",
                                             "foam_scene_depth",
                                             "foam_visibility",
                                             "foam_depth",
                                             "foam_thickness",
                                             "foam_intensity",
                                             "foam_tiles",
                                             "foam_occlusion",
                                             "foam_blur",
                                             "composite"};
  EXPECT_EQ(names(plan.passes), expected);
  EXPECT_TRUE(plan.skipped.empty());
}

TEST(FramePlan, EmptyFrameRunsBackgroundAndCompositeOnly) {
  const FramePlan plan = planFrame({0, 0, 0, "plane_fit"});
  EXPECT_EQ(names(plan.passes), (std::vector<std::string>{"background", "composite"}));
  ASSERT_EQ(plan.skipped.size(), 23u);
  EXPECT_EQ(plan.skipped.front().name, "occluder_depth");
  EXPECT_EQ(reasonFor(plan, "occluder_depth"), "no occluders");
  EXPECT_EQ(reasonFor(plan, "liquid_mesh_depth"), "no liquid mesh");
  for (const std::string& pass : kLightPasses)
    EXPECT_EQ(reasonFor(plan, pass), "no lights in the scene");
  EXPECT_EQ(reasonFor(plan, "refraction"), "no liquid particles in view");
  EXPECT_EQ(reasonFor(plan, "smoothing"), "no aggregate particles in view");
  EXPECT_EQ(reasonFor(plan, "rim_normals"), "no aggregate particles in view");
  EXPECT_EQ(reasonFor(plan, "liquid_tiles"), "no liquid particles in view");
  for (const std::string& pass : kFoamPasses)
    EXPECT_EQ(reasonFor(plan, pass), "no foam particles in view");
}

TEST(FramePlan, SplashesAloneNeedNoSmoothing) {
  const FramePlan plan = planFrame({10, 0, 0, "plane_fit"});
  EXPECT_TRUE(plan.runs(Pass::SplashDepthLayers));
  EXPECT_FALSE(plan.runs(Pass::AggregateDepthLayers));
  EXPECT_FALSE(plan.runs(Pass::Smoothing));
  EXPECT_TRUE(plan.runs(Pass::Refraction));
  EXPECT_EQ(reasonFor(plan, "aggregate_depth_layers"), "no aggregate particles in view");
}

TEST(FramePlan, SmoothingNoneSkipsSmoothingOnly) {
  const FramePlan plan = planFrame({0, 10, 0, "none"});
  EXPECT_TRUE(plan.runs(Pass::AggregateDepthLayers));
  EXPECT_FALSE(plan.runs(Pass::Smoothing));
  EXPECT_EQ(reasonFor(plan, "smoothing"), "liquid.smoothing is none");
  EXPECT_TRUE(plan.runs(Pass::RimNormals));  // the ellipsoids' own rim flattens as a filter's does
  EXPECT_TRUE(plan.runs(Pass::Refraction));
}

// The rim normals bend the aggregated body's front layer: not without one, nor when it is off.
TEST(FramePlan, RimNormalsNeedTheBodysFrontLayer) {
  EXPECT_EQ(reasonFor(planFrame({10, 0, 0, "plane_fit"}), "rim_normals"), "no aggregate particles in view");
  FrameContents off{0, 10, 0, "plane_fit"};
  off.rimNormals = false;
  EXPECT_EQ(reasonFor(planFrame(off), "rim_normals"), "liquid.rim_normals is off");
  FrameContents underWater{0, 10, 0, "plane_fit"};
  underWater.cameraInLiquid = true;
  EXPECT_EQ(reasonFor(planFrame(underWater), "rim_normals"),
            "the camera is under water: no front layer is drawn");
  FrameContents marched{0, 10, 0, "plane_fit"};
  marched.surface = "raymarch";
  EXPECT_EQ(reasonFor(planFrame(marched), "rim_normals"), "the ray-marched surface replaces the front layer");
  FrameContents nothingRead{0, 10, 0, "plane_fit"};
  nothingRead.compositeWanted = nothingRead.liquidLayersWanted = nothingRead.foamLayersWanted = false;
  EXPECT_EQ(reasonFor(planFrame(nothingRead), "rim_normals"),
            "no liquid layer, composite or foam asked for (--layers)");
  EXPECT_TRUE(planFrame({0, 10, 0, "plane_fit"}).runs(Pass::RimNormals));
}

// The footprint averages what the refraction looked up: it runs after it, with it, and not with a zero-width
// pixel filter.
TEST(FramePlan, TheFootprintFollowsTheRefraction) {
  const FramePlan plan = planFrame({10, 0, 0, "plane_fit"});
  ASSERT_TRUE(plan.runs(Pass::RefractionFootprint));
  const auto refraction = std::find(plan.passes.begin(), plan.passes.end(), Pass::Refraction);
  EXPECT_EQ(std::next(refraction),
            std::find(plan.passes.begin(), plan.passes.end(), Pass::RefractionFootprint));
  EXPECT_EQ(reasonFor(planFrame({0, 0, 5, "plane_fit"}), "refraction_footprint"),
            "no liquid particles in view");
  FrameContents sharp{10, 0, 0, "plane_fit"};
  sharp.pixelFilterWidth = 0.0f;
  EXPECT_EQ(reasonFor(planFrame(sharp), "refraction_footprint"), "liquid.pixel_filter_width is 0");
  EXPECT_TRUE(planFrame(sharp).runs(Pass::Refraction));
}

TEST(FramePlan, FoamWithoutLiquidRunsTheFoamPasses) {
  const FramePlan plan = planFrame({0, 0, 5, "plane_fit"});
  EXPECT_FALSE(plan.runs(Pass::Refraction));
  for (Pass pass : {Pass::FoamSceneDepth, Pass::FoamDepth, Pass::FoamThickness, Pass::FoamIntensity,
                    Pass::FoamOcclusion, Pass::FoamBlur})
    EXPECT_TRUE(plan.runs(pass)) << passName(pass);
}

// Lights: the light passes run when a light sees the liquid (one sun's or spot's shadow found by the lit
// background itself); caustics need a sun or a spot and light.caustics; a scene whose lights see no liquid
// says so.
FrameContents withLights(std::size_t lights, std::size_t seeing, std::size_t causticLights, bool caustics) {
  FrameContents contents{0, 10, 0, "plane_fit"};
  contents.lights = lights;
  contents.lightsSeeingLiquid = seeing;
  contents.causticLights = causticLights;
  contents.caustics = caustics;
  return contents;
}

TEST(FramePlan, LightsRunTheLightPasses) {
  const FramePlan pointOnly = planFrame(withLights(1, 1, 0, true));
  EXPECT_TRUE(pointOnly.runs(Pass::LiquidShadow));
  EXPECT_TRUE(pointOnly.runs(Pass::LitBackground));
  EXPECT_EQ(reasonFor(pointOnly, "caustics"), "no sun or spot light sees the liquid");
  const FramePlan causticsOff = planFrame(withLights(1, 1, 1, false));
  EXPECT_EQ(reasonFor(causticsOff, "caustics"), "light.caustics is off");
  const FramePlan unseen = planFrame(withLights(1, 0, 0, true));
  for (const std::string& pass : kLightPasses)
    EXPECT_EQ(reasonFor(unseen, pass), "no light sees the liquid");
  // One sun: the lit background finds its shadow, and its layers and caustics follow the sky's passes.
  const FramePlan oneSun = planFrame(withLights(1, 1, 1, true));
  const std::vector<std::string> oneSunOrder = {"sky_occlusion", "light_depth_layers", "caustics",
                                                "lit_tiles", "lit_background"};
  std::vector<std::string> lightPassesRun;
  for (const std::string& pass : names(oneSun.passes))
    if (std::find(kLightPasses.begin(), kLightPasses.end(), pass) != kLightPasses.end())
      lightPassesRun.push_back(pass);
  EXPECT_EQ(lightPassesRun, oneSunOrder);
  EXPECT_EQ(reasonFor(oneSun, "liquid_shadow"), "the lit background finds the one light's shadow itself");
  // Two suns, or one without the sky occlusion's samples, add their shadows up in the shadow pass.
  const FramePlan twoSuns = planFrame(withLights(2, 2, 2, true));
  for (Pass pass :
       {Pass::LightDepthLayers, Pass::LiquidShadow, Pass::Caustics, Pass::SkyOcclusion, Pass::LitBackground})
    EXPECT_TRUE(twoSuns.runs(pass)) << passName(pass);
  FrameContents noSkyOcclusion = withLights(1, 1, 1, true);
  noSkyOcclusion.skyOcclusionDirections = 0;
  const FramePlan withoutSky = planFrame(noSkyOcclusion);
  EXPECT_TRUE(withoutSky.runs(Pass::LitBackground));
  EXPECT_TRUE(withoutSky.runs(Pass::LiquidShadow));
  EXPECT_EQ(reasonFor(withoutSky, "sky_occlusion"), "light.sky_occlusion_directions is 0");
  // The lit tiles are found from the sky occlusion's samples: without them every pixel is lit.
  EXPECT_EQ(reasonFor(withoutSky, "lit_tiles"), "light.sky_occlusion_directions is 0");
  EXPECT_TRUE(twoSuns.runs(Pass::LitTiles));
  FrameContents everyPixel = withLights(1, 1, 1, true);
  everyPixel.skipUnlitTiles = false;
  EXPECT_EQ(reasonFor(planFrame(everyPixel), "lit_tiles"), "light.skip_unlit_tiles is off");
  EXPECT_TRUE(planFrame(everyPixel).runs(Pass::LitBackground));
}

// The world's light alone (light.sky_without_lamps): without a lamp that sees the liquid the sky's passes and
// the lit background run, in the order a lamp's frame runs them, and the lamps' own passes are skipped with
// the lamps' reason; without the sky occlusion's samples the lit background still runs; when nothing reads
// the lit background nothing runs.
TEST(FramePlan, TheWorldAloneRunsTheSkysPassesOnly) {
  for (const FrameContents& lampless : {withLights(0, 0, 0, true), withLights(1, 0, 0, true)}) {
    FrameContents contents = lampless;
    contents.worldLightsAlone = true;
    const FramePlan plan = planFrame(contents);
    const std::string lamps = contents.lights == 0 ? "no lights in the scene" : "no light sees the liquid";
    for (const char* pass : {"light_depth_layers", "liquid_shadow", "caustics"})
      EXPECT_EQ(reasonFor(plan, pass), lamps) << pass;
    std::vector<std::string> lightPassesRun;
    for (const std::string& pass : names(plan.passes))
      if (std::find(kLightPasses.begin(), kLightPasses.end(), pass) != kLightPasses.end())
        lightPassesRun.push_back(pass);
    EXPECT_EQ(lightPassesRun, (std::vector<std::string>{"sky_occlusion", "lit_tiles", "lit_background"}));
    FrameContents withoutSamples = contents;
    withoutSamples.skyOcclusionDirections = 0;
    const FramePlan withoutSky = planFrame(withoutSamples);
    EXPECT_TRUE(withoutSky.runs(Pass::LitBackground));
    EXPECT_EQ(reasonFor(withoutSky, "sky_occlusion"), "light.sky_occlusion_directions is 0");
    FrameContents nothingRead = contents;
    nothingRead.compositeWanted = nothingRead.liquidLayersWanted = nothingRead.foamLayersWanted = false;
    nothingRead.lightLayersWanted = false;
    for (const std::string& pass : kLightPasses)
      EXPECT_EQ(reasonFor(planFrame(nothingRead), pass), lamps) << pass;
  }
}

// --layers: the light passes run for the light layers alone, and not when nothing reads the lit background.
TEST(FramePlan, LightPassesFollowTheLayerSelection) {
  FrameContents lightOnly = withLights(1, 1, 1, true);
  lightOnly.compositeWanted = lightOnly.liquidLayersWanted = lightOnly.foamLayersWanted = false;
  const FramePlan plan = planFrame(lightOnly);
  for (Pass pass : {Pass::LightDepthLayers, Pass::Caustics, Pass::SkyOcclusion, Pass::LitBackground})
    EXPECT_TRUE(plan.runs(pass)) << passName(pass);
  EXPECT_FALSE(plan.runs(Pass::Refraction));
  FrameContents nothing = lightOnly;
  nothing.lightLayersWanted = false;
  for (const std::string& pass : kLightPasses)
    EXPECT_EQ(reasonFor(planFrame(nothing), pass),
              "no light layer, liquid layer, composite or foam asked for (--layers)");
}

TEST(FramePlan, MeshesRunTheirDepthPrepassesWithoutParticles) {
  FrameContents contents{0, 0, 0, "plane_fit"};
  contents.occluderMeshes = 1;
  contents.liquidMesh = true;
  const FramePlan plan = planFrame(contents);
  EXPECT_TRUE(plan.runs(Pass::OccluderDepth));
  EXPECT_TRUE(plan.runs(Pass::LiquidMeshDepth));
  EXPECT_FALSE(plan.runs(Pass::Refraction));
}

TEST(FramePlan, EveryPassIsEitherRunOrSkippedExactlyOnce) {
  for (std::size_t splash : {0, 1})
    for (std::size_t aggregate : {0, 1})
      for (std::size_t foam : {0, 1})
        for (const char* smoothing : {"plane_fit", "none"}) {
          for (int wanted = 0; wanted < 16; ++wanted) {
            FrameContents contents{splash, aggregate, foam, smoothing};
            contents.occluderMeshes = splash;
            contents.liquidMesh = aggregate > 0;
            contents.lights = splash + foam;
            contents.lightsSeeingLiquid = foam;
            contents.causticLights = aggregate * foam;
            contents.caustics = smoothing[0] == 'p';
            contents.compositeWanted = wanted & 1;
            contents.liquidLayersWanted = wanted & 2;
            contents.foamLayersWanted = wanted & 4;
            contents.intermediateWanted = wanted & 8;
            const FramePlan plan = planFrame(contents);
            std::vector<std::string> all = names(plan.passes);
            for (const SkippedPass& skipped : plan.skipped) {
              EXPECT_FALSE(skipped.reason.empty());
              all.push_back(skipped.name);
            }
            std::sort(all.begin(), all.end());
            EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end());
            EXPECT_EQ(all.size(), 25u);
            // A pass runs only when what it reads runs.
            if (plan.runs(Pass::RefractionFootprint)) EXPECT_TRUE(plan.runs(Pass::Refraction));
            if (plan.runs(Pass::RimNormals)) EXPECT_TRUE(plan.runs(Pass::AggregateDepthLayers));
            if (plan.runs(Pass::LiquidTiles))
              EXPECT_TRUE(plan.runs(Pass::SplashDepthLayers) || plan.runs(Pass::AggregateDepthLayers));
            if (plan.runs(Pass::SkyOcclusion)) EXPECT_TRUE(plan.runs(Pass::LitBackground));
            if (plan.runs(Pass::LitTiles))
              EXPECT_TRUE(plan.runs(Pass::SkyOcclusion) && plan.runs(Pass::LitBackground));
            if (plan.runs(Pass::Smoothing)) EXPECT_TRUE(plan.runs(Pass::AggregateDepthLayers));
            if (plan.runs(Pass::FoamSceneDepth) && (splash || aggregate))
              EXPECT_TRUE(plan.runs(Pass::Refraction));
            if (plan.runs(Pass::FoamVisibility)) EXPECT_TRUE(plan.runs(Pass::FoamSceneDepth));
          }
        }
}

TEST(FramePlan, FoamDrawnWithoutCullingSkipsItsVisibility) {
  FrameContents contents{100, 1000, 50, "plane_fit"};
  contents.foamCulling = false;
  const FramePlan plan = planFrame(contents);
  EXPECT_FALSE(plan.runs(Pass::FoamVisibility));
  EXPECT_TRUE(plan.runs(Pass::FoamDepth));
  EXPECT_EQ(reasonFor(plan, "foam_visibility"), "foam.cull_hidden is off");
}

TEST(FramePlan, EmptyTilesShadedWhenAskedSkipsTheTilePass) {
  FrameContents contents{100, 1000, 50, "plane_fit"};
  contents.skipEmptyTiles = false;
  const FramePlan plan = planFrame(contents);
  EXPECT_FALSE(plan.runs(Pass::LiquidTiles));
  EXPECT_TRUE(plan.runs(Pass::Smoothing));
  EXPECT_TRUE(plan.runs(Pass::Refraction));
  EXPECT_EQ(reasonFor(plan, "liquid_tiles"), "liquid.skip_empty_tiles is off");
  EXPECT_TRUE(planFrame({10, 0, 0, "none"}).runs(Pass::LiquidTiles)) << "splashes alone are refracted";
  EXPECT_TRUE(plan.runs(Pass::FoamTiles)) << "the foam's own parameter";
  contents.skipEmptyFoamTiles = false;
  EXPECT_EQ(reasonFor(planFrame(contents), "foam_tiles"), "foam.skip_empty_tiles is off");
}

FrameContents withLayers(bool composite, bool liquid, bool foam) {
  FrameContents contents{100, 1000, 50, "plane_fit"};
  contents.compositeWanted = composite;
  contents.liquidLayersWanted = liquid;
  contents.foamLayersWanted = foam;
  return contents;
}

TEST(FramePlan, LiquidLayersAloneSkipFoamAndComposite) {
  const FramePlan plan = planFrame(withLayers(false, true, false));
  EXPECT_TRUE(plan.runs(Pass::Refraction));
  EXPECT_TRUE(plan.runs(Pass::Smoothing));
  EXPECT_FALSE(plan.runs(Pass::Composite));
  EXPECT_EQ(reasonFor(plan, "composite"), "composite not asked for (--layers)");
  for (const std::string& pass : kFoamPasses)
    EXPECT_EQ(reasonFor(plan, pass), "no foam layer or composite asked for (--layers)");
}

TEST(FramePlan, FoamLayersAloneStillNeedTheLiquidThatCoversTheFoam) {
  const FramePlan plan = planFrame(withLayers(false, false, true));
  EXPECT_TRUE(plan.runs(Pass::Refraction));
  EXPECT_TRUE(plan.runs(Pass::FoamBlur));
  EXPECT_FALSE(plan.runs(Pass::Composite));
}

TEST(FramePlan, FoamLayersAloneWithoutFoamInViewNeedNoLiquid) {
  FrameContents contents = withLayers(false, false, true);
  contents.foamParticles = 0;
  const FramePlan plan = planFrame(contents);
  EXPECT_EQ(names(plan.passes), (std::vector<std::string>{"background"}));
  EXPECT_EQ(reasonFor(plan, "refraction"), "no liquid layer, composite or foam asked for (--layers)");
  EXPECT_EQ(reasonFor(plan, "aggregate_depth_layers"),
            "no liquid layer, composite or foam asked for (--layers)");
}

TEST(FramePlan, IntermediateLayersKeepTheDepthLayers) {
  FrameContents contents = withLayers(false, false, false);
  contents.intermediateWanted = true;
  const FramePlan plan = planFrame(contents);
  EXPECT_TRUE(plan.runs(Pass::AggregateDepthLayers));
  EXPECT_TRUE(plan.runs(Pass::Smoothing));
  EXPECT_FALSE(plan.runs(Pass::Refraction));
}

}  // namespace
}  // namespace spindrift

namespace spindrift {
namespace {

FrameContents withSurface(std::size_t splashes, std::size_t aggregates, const char* surface) {
  FrameContents contents;
  contents.splashParticles = splashes;
  contents.aggregateParticles = aggregates;
  contents.surface = surface;
  return contents;
}

TEST(FramePlan, RaymarchedSurfaceRunsBetweenSmoothingAndRefraction) {
  const FramePlan plan = planFrame(withSurface(10, 100, "raymarch"));
  const std::vector<std::string> passes = names(plan.passes);
  const auto position = [&](const char* name) {
    return std::find(passes.begin(), passes.end(), name) - passes.begin();
  };
  ASSERT_TRUE(plan.runs(Pass::RaymarchSurface));
  EXPECT_EQ(position("raymarch_surface"), position("smoothing") + 1);
  EXPECT_FALSE(plan.runs(Pass::RimNormals));
  EXPECT_EQ(position("refraction"), position("raymarch_surface") + 1);
  EXPECT_FALSE(planFrame(withSurface(10, 100, "screen")).runs(Pass::RaymarchSurface));
  const FramePlan empty = planFrame(withSurface(0, 0, "raymarch"));
  EXPECT_FALSE(empty.runs(Pass::RaymarchSurface));
  EXPECT_EQ(reasonFor(empty, "raymarch_surface"), "no liquid particles in view");
}

}  // namespace
}  // namespace spindrift
