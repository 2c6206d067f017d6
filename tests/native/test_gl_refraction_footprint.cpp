// The background over each liquid pixel's footprint (liquid.pixel_filter_width,
// shaders/refraction_footprint.frag): where a ball of water shrinks a fine checker behind it, as a lens far
// from its object does, a path tracer's pixel averages the many checks it covers to their mean; one ray per
// pixel reads one check and aliases. GL tests on llvmpipe; the footprints are measured here from the
// refraction's own lookups, and the checks' mean is known.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "BackgroundFiles.h"
#include "LiquidTestScenes.h"
#include "TempDirectory.h"
#include "spindrift/Scene.h"

using namespace spindrift;
using namespace liquid_test;

namespace {

constexpr int kWidth = 200, kHeight = 150;
const glm::vec3 kBallCentre(0.0f, 0.0f, -3.0f);
constexpr float kBallRadius = 0.6f, kSpacing = 0.04f, kParticleRadius = 0.03f;
constexpr float kPlaneDepth = 12.0f;  // far behind the ball, which shrinks it as a lens past its focus

// The camera at the origin looking down -Z over a plane of one-texel checks, black and white.
Scene sceneOverChecks(const TempDirectory& directory) {
  Scene scene;
  scene.camera.width = kWidth;
  scene.camera.height = kHeight;
  scene.camera.fovYDegrees = 40.0f;
  scene.background.image = directory.path() / "checks.exr";
  writeBackgroundExr(
      scene.background.image, kWidth, kHeight,
      [](int column, int row) { return glm::vec3(float((column + row) % 2)); },
      [](int, int) { return kPlaneDepth; });
  scene.parameters.liquid.absorption = 0.0f;  // the checks come through unchanged but for Fresnel
  return scene;
}

Particles latticeBall() {
  return liquid_test::latticeBall(kBallCentre, kBallRadius, kSpacing, kParticleRadius);
}

// Where a pixel's final ray reads the background, in texels (refraction_uv; rows counted from the top as the
// layers hold them), or nothing.
struct Lookup {
  bool found = false;
  glm::vec2 texel{0.0f};
};
Lookup lookupAt(const RenderResult& result, int column, int row) {
  const ImageLayer& uv = *result.layer("refraction_uv");
  if (at(uv, kWidth, column, row, 2) < 0.5f) return {};
  return {true, {at(uv, kWidth, column, row, 0) * kWidth, at(uv, kWidth, column, row, 1) * kHeight}};
}

// The background the pixel's refracted light shows: (liquid - reflection) / transmittance, grey.
float seenBackground(const RenderResult& result, int column, int row) {
  const float liquid = at(*result.layer("liquid"), kWidth, column, row, 1);
  const float reflected = at(*result.layer("reflection"), kWidth, column, row, 1);
  return (liquid - reflected) / at(*result.layer("transmittance"), kWidth, column, row, 1);
}

// The pixels whose footprint is a smooth shrink of at least 3 checks each way: the steps to the neighbours on
// either side along each axis are longer than 3 texels and agree within a quarter.
std::vector<std::pair<int, int>> shrunkPixels(const RenderResult& result) {
  std::vector<std::pair<int, int>> shrunk;
  for (int row = 1; row + 1 < kHeight; ++row)
    for (int column = 1; column + 1 < kWidth; ++column) {
      const Lookup centre = lookupAt(result, column, row);
      if (!centre.found) continue;
      bool smooth = true;
      for (const glm::ivec2 axis : {glm::ivec2(1, 0), glm::ivec2(0, 1)}) {
        const Lookup before = lookupAt(result, column - axis.x, row - axis.y);
        const Lookup after = lookupAt(result, column + axis.x, row + axis.y);
        if (!before.found || !after.found) {
          smooth = false;
          continue;
        }
        const float stepBefore = glm::length(centre.texel - before.texel);
        const float stepAfter = glm::length(after.texel - centre.texel);
        smooth = smooth && stepBefore > 3.0f && stepAfter > 3.0f &&
                 std::abs(stepBefore - stepAfter) < 0.25f * std::max(stepBefore, stepAfter);
      }
      if (smooth) shrunk.emplace_back(column, row);
    }
  return shrunk;
}

// How far from the checks' mean (0.5) the shrunk pixels' backgrounds are, on average.
float meanDistanceFromTheChecksMean(const RenderResult& result,
                                    const std::vector<std::pair<int, int>>& pixels) {
  double sum = 0.0;
  for (const auto& [column, row] : pixels)
    sum += std::abs(seenBackground(result, column, row) - 0.5f);
  return float(sum / double(pixels.size()));
}

}  // namespace

// Through the ball the checks shrink to several per pixel (434 pixels here): each such pixel shows their
// mean, within 0.04 on average (0.008 measured). Without the footprint (a width of 0: one bilinear lookup at
// the ray's end, between two or four checks) the same pixels read 0.13 from the mean on average.
TEST(GLRefractionFootprint, ChecksTheLensShrinksAverageToTheirMean) {
  TempDirectory directory;
  Scene scene = sceneOverChecks(directory);
  const RenderResult averaged = renderer().renderParticles(scene, latticeBall(), 1);
  expectAllChannelsFinite(averaged);
  const std::vector<std::pair<int, int>> shrunk = shrunkPixels(averaged);
  ASSERT_GT(shrunk.size(), 100u) << "the ball shrinks too few pixels' background: the scene is wrong";
  EXPECT_LT(meanDistanceFromTheChecksMean(averaged, shrunk), 0.04f);

  scene.parameters.liquid.pixel_filter_width = 0.0f;
  const RenderResult single = renderer().renderParticles(scene, latticeBall(), 1);
  expectAllChannelsFinite(single);
  EXPECT_GT(meanDistanceFromTheChecksMean(single, shrunk), 0.1f);
}

// Where the refraction does not shrink the background (the plane just behind the ball, magnified) no pixel is
// averaged: the liquid is what the width of 0 gives, to the bit.
TEST(GLRefractionFootprint, AMagnifiedBackgroundIsNotAveraged) {
  TempDirectory directory;
  Scene scene = sceneOverChecks(directory);
  scene.background.image = directory.path() / "near.exr";
  writeBackgroundExr(
      scene.background.image, kWidth, kHeight,
      [](int column, int row) { return glm::vec3(float((column + row) % 2)); },
      [](int, int) { return 3.7f; });  // 0.1 behind the ball's back
  const RenderResult averaged = renderer().renderParticles(scene, latticeBall(), 1);
  expectAllChannelsFinite(averaged);
  EXPECT_GT(averaged.stats.liquid.liquidPixels, 3000u);
  scene.parameters.liquid.pixel_filter_width = 0.0f;
  const RenderResult single = renderer().renderParticles(scene, latticeBall(), 1);
  int differing = 0, liquidPixels = 0;
  for (int row = 0; row < kHeight; ++row)
    for (int column = 0; column < kWidth; ++column) {
      if (at(*averaged.layer("liquid"), kWidth, column, row, 3) <= 0.0f) continue;
      ++liquidPixels;
      differing += at(*averaged.layer("liquid"), kWidth, column, row, 1) !=
                   at(*single.layer("liquid"), kWidth, column, row, 1);
    }
  // The ball's rim still shrinks what it refracts; its inner part magnifies.
  EXPECT_LT(differing, liquidPixels / 4);
}

// A ball half outside the image: footprints at the image's edge clamp their taps, and every channel stays
// finite.
TEST(GLRefractionFootprint, ABallCutByTheImagesEdgeStaysFinite) {
  TempDirectory directory;
  Scene scene = sceneOverChecks(directory);
  Particles ball;
  const Particles centred = latticeBall();
  for (std::size_t i = 0; i < centred.size(); ++i)
    ball.append(centred.positions[i] + glm::vec3(1.3f, 0.9f, 0.0f), kParticleRadius, ParticleKind::Liquid,
                0.0f, glm::vec3(0.0f));
  const RenderResult result = renderer().renderParticles(scene, ball, 1);
  expectAllChannelsFinite(result);
  EXPECT_GT(result.stats.liquid.liquidPixels, 500u);
}
