// The splash/aggregate split and plane-fit smoothing in the whole pipeline: GL tests on llvmpipe.
#include <gtest/gtest.h>

#include "BackgroundFiles.h"
#include "LiquidTestScenes.h"
#include "OpticsReference.h"
#include "TempDirectory.h"

using namespace spindrift;
using namespace liquid_test;

namespace {

constexpr int kWidth = 128, kHeight = 96;
constexpr float kRadius = 0.05f;
constexpr float kSpacing = 0.9f * kRadius;  // FLIP-like: particles overlap

Scene frontalScene(const TempDirectory& directory, const glm::vec3& backgroundColour) {
  Scene scene;
  scene.camera = Camera::lookAt(kWidth, kHeight, 30.0f, {0, 0, 3}, {0, 0, 0}, {0, 1, 0});
  scene.background.color = glm::vec3(0.0f);
  scene.background.image = directory.path() / "wall.exr";
  writeBackgroundExr(
      scene.background.image, kWidth, kHeight, [&](int, int) { return backgroundColour; },
      [](int, int) { return 10.0f; });
  return scene;
}

// A slab of liquid facing the camera: x, y in [-0.5, 0.5], z in [-thickness / 2, thickness / 2].
std::vector<glm::vec3> slab(float layers) {
  const float halfThickness = 0.5f * (layers - 1) * kSpacing;
  return block({-0.5f, -0.5f, -halfThickness}, {0.5f, 0.5f, halfThickness}, kSpacing);
}

}  // namespace

// Beer-Lambert through a flat slab of aggregated particles, seen head on: every channel must follow
// exp(-a c_a l) for one path length l, and l must be the slab's thickness to within a particle radius.
TEST(GLLiquidLayers, SlabFollowsBeerLambert) {
  TempDirectory directory;
  Scene scene = frontalScene(directory, glm::vec3(1.0f));
  scene.parameters.liquid.absorption_rgb = {1.0f, 2.0f, 4.0f};
  const int layers = 9;
  const RenderResult result = renderer().renderParticles(scene, particlesOf(slab(layers), kRadius), 1);
  expectAllChannelsFinite(result);
  EXPECT_GT(result.stats.liquid.aggregateParticles, 1000u);
  const double transmission = std::pow(1.0 - optics::schlick(1.0, scene.parameters.liquid.ior), 2.0);
  // Average over the slab's middle, away from its rim.
  glm::dvec3 mean(0.0);
  double meanThickness = 0.0;
  int count = 0;
  for (int row = kHeight / 2 - 8; row < kHeight / 2 + 8; ++row)
    for (int column = kWidth / 2 - 8; column < kWidth / 2 + 8; ++column) {
      for (int c = 0; c < 3; ++c)
        mean[c] += at(*result.layer("liquid"), kWidth, column, row, c);
      meanThickness += at(*result.layer("thickness"), kWidth, column, row, 0);
      ++count;
    }
  mean /= count;
  meanThickness /= count;
  // Two channels give the path length without knowing the transmission; the third checks it.
  const double pathLength = std::log(mean.r / mean.b) / (4.0 - 1.0);
  const double geometricThickness = (layers - 1) * kSpacing;
  std::printf(
      "slab: path length from colour %.4f, thickness layer %.4f, particle centres span %.4f (r = %.3f)\n",
      pathLength, meanThickness, geometricThickness, kRadius);
  EXPECT_GT(pathLength, geometricThickness);
  // Each face stands about a radius beyond its particles' centres (liquid.reach_radius), give or take its
  // bumps.
  EXPECT_LT(pathLength, geometricThickness + 2.2 * kRadius);
  EXPECT_NEAR(meanThickness, pathLength, 0.05 * pathLength);
  EXPECT_NEAR(mean.g, transmission * std::exp(-2.0 * pathLength), 0.03 * mean.g);
}

// The paper's Problem 1: a splash in front of the body. With split layers the refracted ray finds the
// splash's own back surface (a path of about 2r through it); with merged layers the splash's back is lost and
// the path runs on to the back of the body.
TEST(GLLiquidLayers, SplitLayersFindTheSplashBackSurfaceAndMergedDoNot) {
  TempDirectory directory;
  Scene scene = frontalScene(directory, glm::vec3(1.0f));
  // No smoothing, so that only the layers differ (smoothing would also flatten the merged splash into the
  // body: the paper's Problem 2, measured in GLDepthSmoothing).
  scene.parameters.liquid.smoothing = "none";
  std::vector<glm::vec3> positions = slab(9);
  const glm::vec3 splash(0.0f, 0.0f, 0.6f);  // 0.4 in front of the slab: far outside any neighbourhood
  positions.push_back(splash);
  const glm::vec3 pixel = scene.camera.pixelAndDepthFromWorld(splash);
  const int column = int(pixel.x), row = int(pixel.y);

  const RenderResult split = renderer().renderParticles(scene, particlesOf(positions, kRadius), 1);
  expectAllChannelsFinite(split);
  EXPECT_EQ(split.stats.liquid.splashParticles, 1u);
  EXPECT_EQ(at(*split.layer("liquid_class"), kWidth, column, row, 0), 1.0f)
      << "the first surface is the splash";
  const float splitThickness = at(*split.layer("thickness"), kWidth, column, row, 0);

  scene.parameters.liquid.layers = "merged";
  const RenderResult merged = renderer().renderParticles(scene, particlesOf(positions, kRadius), 1);
  expectAllChannelsFinite(merged);
  EXPECT_EQ(merged.stats.liquid.splashParticles, 0u);
  const float mergedThickness = at(*merged.layer("thickness"), kWidth, column, row, 0);
  std::printf("splash before body: path in liquid %.4f with split layers, %.4f merged (2r = %.3f)\n",
              splitThickness, mergedThickness, 2 * kRadius);
  // Split: in and out of the splash (about 2r = 0.1), then into the body and out again (about 0.45). Merged:
  // one path from the splash's front (0.65) to the body's back (about -0.23), the air gap counted as liquid.
  EXPECT_GT(split.stats.liquid.raysWithSecondBody, 0u);
  EXPECT_LT(splitThickness, 0.6f);
  EXPECT_GT(mergedThickness, 0.75f);
  EXPECT_GT(mergedThickness - splitThickness, 0.25f) << "the air gap between splash and body";
}
