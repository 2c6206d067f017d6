// The frame's wiring (FramePlan.cpp), checked without a GPU: which passes run for which scene contents, in
// which order, and the reason given for each pass left out.
#include <gtest/gtest.h>

#include <algorithm>
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

const std::vector<std::string> kFoamPasses = {"foam_scene_depth", "foam_depth",     "foam_thickness",
                                              "foam_intensity",   "foam_occlusion", "foam_blur"};

TEST(FramePlan, FullFrameRunsEveryPassInRecipeOrder) {
  const FramePlan plan = planFrame({100, 1000, 50, "plane_fit", 2, true});
  const std::vector<std::string> expected = {"background",
                                             "occluder_depth",
                                             "liquid_mesh_depth",
                                             "splash_depth_layers",
                                             "aggregate_depth_layers",
                                             "smoothing",
                                             "refraction",
                                             "foam_scene_depth",
                                             "foam_depth",
                                             "foam_thickness",
                                             "foam_intensity",
                                             "foam_occlusion",
                                             "foam_blur",
                                             "composite"};
  EXPECT_EQ(names(plan.passes), expected);
  EXPECT_TRUE(plan.skipped.empty());
}

TEST(FramePlan, EmptyFrameRunsBackgroundAndCompositeOnly) {
  const FramePlan plan = planFrame({0, 0, 0, "plane_fit"});
  EXPECT_EQ(names(plan.passes), (std::vector<std::string>{"background", "composite"}));
  ASSERT_EQ(plan.skipped.size(), 12u);
  EXPECT_EQ(plan.skipped.front().name, "occluder_depth");
  EXPECT_EQ(reasonFor(plan, "occluder_depth"), "no occluders");
  EXPECT_EQ(reasonFor(plan, "liquid_mesh_depth"), "no liquid mesh");
  EXPECT_EQ(reasonFor(plan, "refraction"), "no liquid particles in view");
  EXPECT_EQ(reasonFor(plan, "smoothing"), "no aggregate particles in view");
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
  EXPECT_TRUE(plan.runs(Pass::Refraction));
}

TEST(FramePlan, FoamWithoutLiquidRunsTheFoamPasses) {
  const FramePlan plan = planFrame({0, 0, 5, "plane_fit"});
  EXPECT_FALSE(plan.runs(Pass::Refraction));
  for (Pass pass : {Pass::FoamSceneDepth, Pass::FoamDepth, Pass::FoamThickness, Pass::FoamIntensity,
                    Pass::FoamOcclusion, Pass::FoamBlur})
    EXPECT_TRUE(plan.runs(pass)) << passName(pass);
}

TEST(FramePlan, MeshesRunTheirDepthPrepassesWithoutParticles) {
  const FramePlan plan = planFrame({0, 0, 0, "plane_fit", 1, true});
  EXPECT_TRUE(plan.runs(Pass::OccluderDepth));
  EXPECT_TRUE(plan.runs(Pass::LiquidMeshDepth));
  EXPECT_FALSE(plan.runs(Pass::Refraction));
}

TEST(FramePlan, EveryPassIsEitherRunOrSkippedExactlyOnce) {
  for (std::size_t splash : {0, 1})
    for (std::size_t aggregate : {0, 1})
      for (std::size_t foam : {0, 1})
        for (const char* smoothing : {"plane_fit", "none"}) {
          const FramePlan plan = planFrame({splash, aggregate, foam, smoothing, splash, aggregate > 0});
          std::vector<std::string> all = names(plan.passes);
          for (const SkippedPass& skipped : plan.skipped) {
            EXPECT_FALSE(skipped.reason.empty());
            all.push_back(skipped.name);
          }
          std::sort(all.begin(), all.end());
          EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end());
          EXPECT_EQ(all.size(), 14u);
        }
}

}  // namespace
}  // namespace spindrift
