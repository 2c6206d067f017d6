// Hard cases for the liquid pipeline, each named after its case: every channel of every layer must stay
// finite, and each case checks what it is about. GL tests on llvmpipe.
#include <gtest/gtest.h>

#include <random>

#include <glm/trigonometric.hpp>

#include "LiquidTestScenes.h"
#include "framedata/PixelTiles.h"

using namespace spindrift;
using namespace liquid_test;

namespace {

Scene sceneLookingAt(const glm::vec3& position, const glm::vec3& target, float nearClip = 0.01f,
                     float farClip = 1000.0f) {
  Scene scene;
  scene.camera = Camera::lookAt(96, 72, 40.0f, position, target, {0, 0, 1});
  scene.camera.nearClip = nearClip;
  scene.camera.farClip = farClip;
  scene.background.color = {0.4f, 0.5f, 0.6f};
  return scene;
}

RenderResult renderCase(const Scene& scene, const std::vector<glm::vec3>& positions, float radius) {
  return renderer().renderParticles(scene, particlesOf(positions, radius), 1);
}

std::size_t coveredPixels(const RenderResult& result) {
  std::size_t covered = 0;
  for (float depth : result.layer("depth")->pixels)
    covered += depth < 1e9f;
  return covered;
}

}  // namespace

TEST(GLLiquidStability, ColinearCluster) {
  std::vector<glm::vec3> positions;
  for (int i = 0; i < 40; ++i)
    positions.emplace_back(0.04f * i - 0.8f, 0.0f, 0.0f);
  const RenderResult result = renderCase(sceneLookingAt({0, -3, 0.5f}, {0, 0, 0}), positions, 0.05f);
  expectAllChannelsFinite(result);
  EXPECT_GT(coveredPixels(result), 50u);
}

TEST(GLLiquidStability, CoplanarCluster) {
  const RenderResult result = renderCase(sceneLookingAt({0, -3, 1}, {0, 0, 0}),
                                         block({-0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, 0.045f), 0.05f);
  expectAllChannelsFinite(result);
  EXPECT_GT(coveredPixels(result), 300u);
}

TEST(GLLiquidStability, SingleNeighbourPair) {
  const RenderResult result =
      renderCase(sceneLookingAt({0, -3, 0}, {0, 0, 0}), {{0, 0, 0}, {0.05f, 0, 0}}, 0.05f);
  expectAllChannelsFinite(result);
  EXPECT_GT(coveredPixels(result), 10u);
}

TEST(GLLiquidStability, CoincidentParticles) {
  const std::vector<glm::vec3> positions(100, glm::vec3(0.1f, 0.0f, 0.0f));
  const RenderResult result = renderCase(sceneLookingAt({0, -3, 0}, {0, 0, 0}), positions, 0.1f);
  expectAllChannelsFinite(result);
  EXPECT_GT(coveredPixels(result), 3u) << "a finite ellipsoid, at least k_n r across";
}

TEST(GLLiquidStability, StraddlingTheNearPlaneAndBehindTheCamera) {
  Scene scene = sceneLookingAt({0, -1, 0}, {0, 0, 0}, 0.1f);
  // Spheres whose centres sit on the near plane, behind the camera, and one in plain view.
  const RenderResult result =
      renderCase(scene, {{0, -0.9f, 0}, {0.05f, -0.9f, 0.02f}, {0, -2, 0}, {0, -1.5f, 0}, {0, 0, 0}}, 0.1f);
  expectAllChannelsFinite(result);
  EXPECT_GT(coveredPixels(result), 10u);
}

TEST(GLLiquidStability, GrazingViewOfAFlatSurface) {
  // A flat sheet of liquid seen from 1 degree above its plane.
  const glm::vec3 eye(0.0f, -3.0f, 3.0f * std::tan(glm::radians(1.0f)));
  const RenderResult result =
      renderCase(sceneLookingAt(eye, {0, 0, 0}), block({-1, -1, -0.05f}, {1, 1, 0}, 0.045f), 0.05f);
  expectAllChannelsFinite(result);
  EXPECT_GT(coveredPixels(result), 50u);
}

TEST(GLLiquidStability, TotalInternalReflection) {
  // A wedge of liquid seen through its flat front face: its back face leans 65 degrees from the view axis,
  // past water's critical angle of 48.8 degrees, so light inside reflects totally.
  std::vector<glm::vec3> wedge;
  for (const glm::vec3& position : block({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, 0.045f))
    if (position.y <= -0.5f + (position.z + 0.5f) * std::tan(glm::radians(65.0f)) * 0.45f)
      wedge.push_back(position);
  Scene scene = sceneLookingAt({0, -3, 0}, {0, 0, 0});
  const RenderResult result = renderCase(scene, wedge, 0.05f);
  expectAllChannelsFinite(result);
  EXPECT_GT(result.stats.liquid.totalInternalReflections, 0u);
}

TEST(GLLiquidStability, CameraInsideTheLiquid) {
  const RenderResult result = renderCase(sceneLookingAt({0, 0, 0}, {0, 1, 0}),
                                         block({-0.6f, -0.6f, -0.6f}, {0.6f, 0.6f, 0.6f}, 0.09f), 0.1f);
  expectAllChannelsFinite(result);
}

// Radii from a fifth of a pixel to 200 pixels on screen (a narrow field of view, so a sphere 200 pixels wide
// on a 72-pixel-high image still lies well in front of the camera).
TEST(GLLiquidStability, ProjectedRadiiFromAFifthOfAPixelTo200Pixels) {
  Scene scene = sceneLookingAt({0, -10, 0}, {0, 0, 0});
  scene.camera.fovYDegrees = 4.0f;
  const float worldPerPixel = 2.0f * std::tan(glm::radians(2.0f)) * 10.0f / 72.0f;
  for (float pixels : {0.2f, 1.0f, 10.0f, 200.0f}) {
    const RenderResult result = renderCase(scene, {{0, 0, 0}}, pixels * worldPerPixel);
    expectAllChannelsFinite(result);
    if (pixels >= 1.0f) EXPECT_GT(coveredPixels(result), 0u) << pixels << " px";
    if (pixels >= 200.0f) EXPECT_EQ(coveredPixels(result), 96u * 72u) << "the sphere fills the frame";
  }
}

// The same small scene scaled from a thousandth of a unit to ten thousand units away.
TEST(GLLiquidStability, DepthRangesFromAThousandthToTenThousandUnits) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> jitter(-1.0f, 1.0f);
  std::vector<glm::vec3> cluster;
  for (int i = 0; i < 200; ++i)
    cluster.emplace_back(0.3f * jitter(random), 0.3f * jitter(random), 0.3f * jitter(random));
  for (float scale : {1e-3f, 1.0f, 1e4f}) {
    Scene scene = sceneLookingAt(glm::vec3(0, -3, 0) * scale, {0, 0, 0}, 0.01f * scale, 1000.0f * scale);
    std::vector<glm::vec3> scaled;
    for (const glm::vec3& p : cluster)
      scaled.push_back(p * scale);
    const RenderResult result = renderCase(scene, scaled, 0.06f * scale);
    expectAllChannelsFinite(result);
    EXPECT_GT(coveredPixels(result), 200u) << "scale " << scale;
  }
}

TEST(GLLiquidStability, EmptyFrame) {
  const RenderResult result = renderCase(sceneLookingAt({0, -3, 0}, {0, 0, 0}), {}, 0.05f);
  expectAllChannelsFinite(result);
  EXPECT_EQ(coveredPixels(result), 0u);
  EXPECT_FALSE(result.stats.skipped.empty());
}

TEST(GLLiquidStability, ASmallBodyAfterALargeOneLeavesNothingOutsideItself) {
  // A renderer keeps its targets from frame to frame: one that drew a large body the frame before must give a
  // small one exactly what it gives it after drawing that small one, in every layer, and leave the pixels
  // outside it empty.
  const Scene scene = sceneLookingAt({0, -3, 0.5f}, {0, 0, 0});
  const std::vector<glm::vec3> large = block({-0.6f, -0.4f, -0.4f}, {0.6f, 0.4f, 0.4f}, 0.05f);
  const std::vector<glm::vec3> small = block({-0.1f, -0.1f, -0.1f}, {0.1f, 0.1f, 0.1f}, 0.05f);
  renderCase(scene, small, 0.05f);
  const RenderResult afterSmall = renderCase(scene, small, 0.05f);
  renderCase(scene, large, 0.05f);
  const RenderResult afterLarge = renderCase(scene, small, 0.05f);
  expectAllChannelsFinite(afterLarge);
  ASSERT_EQ(afterLarge.layers.size(), afterSmall.layers.size());
  for (std::size_t i = 0; i < afterSmall.layers.size(); ++i) {
    SCOPED_TRACE(afterSmall.layers[i].name);
    EXPECT_EQ(afterLarge.layers[i].pixels, afterSmall.layers[i].pixels);
  }
  const ImageLayer& depth = *afterLarge.layer("depth");
  std::size_t covered = 0, outside = 0;
  for (float value : depth.pixels) {
    covered += value < 1e9f;
    outside += value == 1e10f;
  }
  EXPECT_GT(covered, 20u);
  EXPECT_GT(outside, depth.pixels.size() / 2);
  EXPECT_EQ(covered + outside, depth.pixels.size()) << "a pixel without liquid has Blender's empty depth";
  // The stats count what each pass wrote: the refraction shades the tiles that hold liquid twice (its
  // packing and itself), none of them cut by the frame's edge here.
  const std::size_t tilePixels = afterLarge.stats.liquid.tilesShaded * kPixelTileSize * kPixelTileSize;
  EXPECT_GE(tilePixels, covered);
  for (const PassTiming& pass : afterLarge.stats.passes)
    if (pass.name == "refraction") EXPECT_EQ(pass.samplesPassed, 2 * tilePixels);
}
