// The sky view's one-draw depth range (EllipsoidImpostorPass::runDepthRange: the nearest entry and farthest
// exit kept by GL_MIN and GL_MAX blending) against the two draws with opposite depth tests that every other
// view makes: the same layers bit for bit, on a wavy sheet seen from above as the sky sees it, with the
// occlusion test's split (which runDepthRange ignores: it draws every ellipsoid into both layers), and empty
// layers for an empty list. The sky's view is prepared without the occlusion test (prep/LightViews.cpp): the
// range of a deep block drawn whole is the range of what that test leaves, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "LiquidTestScenes.h"
#include "Readback.h"
#include "gl/GlThread.h"
#include "gl/ShaderLibrary.h"
#include "passes/EllipsoidImpostorPass.h"
#include "passes/FrameUniforms.h"
#include "prep/HiddenInterior.h"
#include "prep/LiquidPreparation.h"

using namespace spindrift;

namespace {

// Straight down from far above, as the sky's view looks (prep/LightViews.cpp frames the bounds likewise).
Camera skyLikeView() {
  Camera camera = Camera::lookAt(96, 96, 4.0f, {0.0f, 0.0f, 20.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
  camera.nearClip = 10.0f;
  camera.farClip = 30.0f;
  return camera;
}

struct Layers {
  std::vector<float> front, back;
};

// Both ways of drawing the layers, on one GL thread.
void drawBothWays(const LiquidPreparation& liquid, const Camera& camera, Layers& twoDraws, Layers& oneDraw) {
  GlThread glThread;
  glThread.run([&] {
    const ShaderLibrary shaders(findShaderDirectory());
    FrameUniformBuffer frameUniforms;
    frameUniforms.update(camera);
    EllipsoidImpostorPass impostors(shaders);
    const SurfaceLayers drawn =
        impostors.run(liquid.aggregates, liquid.aggregateLayers, nullptr, camera, nullptr);
    twoDraws = {readLayer(drawn.front.eyeDepth, "front", {"Z"}).pixels,
                readLayer(drawn.back.eyeDepth, "back", {"Z"}).pixels};
    const SurfaceLayers range = impostors.runDepthRange(liquid.aggregates, camera);
    oneDraw = {readLayer(range.front.eyeDepth, "front", {"Z"}).pixels,
               readLayer(range.back.eyeDepth, "back", {"Z"}).pixels};
    const std::vector<float> normal = readLayer(range.front.normal, "normal", {"X", "Y", "Z", "W"}).pixels;
    for (float value : normal)
      ASSERT_EQ(value, 0.0f) << "the depth range leaves its normals zero";
  });
}

// Pixels `expected` covers, and those where `actual`'s front or back layer differs from it; every value of
// `actual` finite.
struct LayerDifferences {
  std::size_t covered = 0, frontDiffers = 0, backDiffers = 0;
};

LayerDifferences compareLayers(const Layers& expected, const Layers& actual) {
  LayerDifferences differences;
  for (std::size_t i = 0; i < expected.front.size(); ++i) {
    EXPECT_TRUE(std::isfinite(actual.front[i]) && std::isfinite(actual.back[i])) << "pixel " << i;
    differences.covered += expected.front[i] < 1e9f;
    differences.frontDiffers += actual.front[i] != expected.front[i];
    differences.backDiffers += actual.back[i] != expected.back[i];
  }
  return differences;
}

}  // namespace

TEST(GLImpostorDepthRange, OneDrawKeepsWhatTheTwoDrawsKeep) {
  const Camera camera = skyLikeView();
  LiquidPreparation liquid = prepareLiquid(liquid_test::wavySheet(5, 11), camera, LiquidParameters{});
  // The occlusion test splits the list into front-only, both and back-only ellipsoids, as it does for the
  // sky's view of a deep body.
  const HiddenInteriorResult hidden = dropHiddenAggregates(liquid, camera, nullptr);
  ASSERT_GT(hidden.occluded.hiddenFromFront + hidden.occluded.hiddenFromBack, 0u)
      << "the test needs a split for the one draw to ignore";
  Layers twoDraws, oneDraw;
  drawBothWays(liquid, camera, twoDraws, oneDraw);

  const LayerDifferences differences = compareLayers(twoDraws, oneDraw);
  RecordProperty("covered_pixels", int(differences.covered));
  EXPECT_GT(differences.covered, 3000u) << "the sheet fills much of the view";
  EXPECT_LT(differences.covered, twoDraws.front.size())
      << "and leaves empty pixels, which both layers must mark";
  EXPECT_EQ(differences.frontDiffers, 0u);
  EXPECT_EQ(differences.backDiffers, 0u);
}

TEST(GLImpostorDepthRange, TheOcclusionTestLeavesTheRangeAsItIs) {
  const Camera camera = skyLikeView();
  const Particles block =
      liquid_test::particlesOf(liquid_test::block({-0.6f, -0.6f, -0.25f}, {0.6f, 0.6f, 0.25f}, 0.05f), 0.05f);
  const LiquidPreparation whole = prepareLiquid(block, camera, LiquidParameters{});
  LiquidPreparation tested = whole;
  const HiddenInteriorResult hidden = dropHiddenAggregates(tested, camera, nullptr);
  ASSERT_GT(hidden.dropped + hidden.occluded.dropped, whole.aggregates.size() / 2)
      << "the test needs a body whose inside the occlusion test leaves out";
  Layers wholeRange, testedRange, unused;
  drawBothWays(whole, camera, unused, wholeRange);
  drawBothWays(tested, camera, unused, testedRange);
  const LayerDifferences differences = compareLayers(wholeRange, testedRange);
  EXPECT_GT(differences.covered, 3000u) << "the block fills much of the view";
  EXPECT_EQ(differences.frontDiffers, 0u);
  EXPECT_EQ(differences.backDiffers, 0u);
}

TEST(GLImpostorDepthRange, EmptyListLeavesBothLayersEmpty) {
  LiquidPreparation nothing;
  Layers twoDraws, oneDraw;
  drawBothWays(nothing, skyLikeView(), twoDraws, oneDraw);
  for (std::size_t i = 0; i < oneDraw.front.size(); ++i) {
    ASSERT_EQ(oneDraw.front[i], 1e10f);
    ASSERT_EQ(oneDraw.back[i], 1e10f);
  }
}
