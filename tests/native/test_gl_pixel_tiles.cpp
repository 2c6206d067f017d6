// Shading only the pixel tiles that hold liquid or foam (liquid.skip_empty_tiles, foam.skip_empty_tiles,
// framedata/PixelTiles.h) changes no value of any layer: every case is rendered both ways, the depth layers
// before and after smoothing included, and compared bit for bit. GL tests on llvmpipe.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/trigonometric.hpp>

#include "LiquidTestScenes.h"
#include "passes/PixelTilePass.h"

using namespace spindrift;
using namespace liquid_test;

namespace {

Scene sceneOfSize(int width, int height, const glm::vec3& position, const glm::vec3& target) {
  Scene scene;
  scene.camera = Camera::lookAt(width, height, 40.0f, position, target, {0, 0, 1});
  scene.background.color = {0.4f, 0.5f, 0.6f};
  return scene;
}

// Liquid and spray over the whole view (a sheet of particles 1 unit in front of the camera, spray at 0.8): a
// frame drawn before a case leaves values in every pixel of every target, which the tiles not shaded must not
// keep.
Particles fillingTheView(const Camera& camera) {
  Particles particles;
  const float tanY = std::tan(glm::radians(camera.fovYDegrees) * 0.5f), tanX = tanY * camera.aspect();
  for (int row = 0; row <= 40; ++row)
    for (int column = 0; column <= 40; ++column) {
      const glm::vec2 ndc(column / 20.0f - 1.0f, row / 20.0f - 1.0f);
      for (const auto& [depth, kind] : {std::pair{1.0f, ParticleKind::Liquid}, {0.8f, ParticleKind::Spray}}) {
        const glm::vec4 inCamera(ndc.x * tanX * depth, ndc.y * tanY * depth, -depth, 1.0f);
        particles.append(glm::vec3(camera.worldFromCamera * inCamera),
                         kind == ParticleKind::Liquid ? 0.03f : 0.01f, kind, 0.0f, glm::vec3(0.0f));
      }
    }
  return particles;
}

// Both ways, on their own renderers (with intermediate layers), the tiled one last so its stats come back;
// each renderer draws a frame that fills the view first.
RenderResult expectSameBothWays(Scene scene, const Particles& particles) {
  static Renderer full, tiled;
  full.setIntermediateLayers(true);
  tiled.setIntermediateLayers(true);
  full.renderParticles(scene, fillingTheView(scene.camera), 1);
  tiled.renderParticles(scene, fillingTheView(scene.camera), 1);
  scene.parameters.liquid.skip_empty_tiles = scene.parameters.foam.skip_empty_tiles = false;
  const RenderResult everyPixel = full.renderParticles(scene, particles, 1);
  scene.parameters.liquid.skip_empty_tiles = scene.parameters.foam.skip_empty_tiles = true;
  const RenderResult liquidTiles = tiled.renderParticles(scene, particles, 1);
  expectAllChannelsFinite(liquidTiles);
  EXPECT_EQ(everyPixel.stats.liquid.tiles, 0u) << "off: no tiles";
  EXPECT_EQ(everyPixel.stats.foam.tiles, 0u);
  EXPECT_LE(liquidTiles.stats.foam.tilesShaded, liquidTiles.stats.foam.tiles);
  EXPECT_EQ(liquidTiles.stats.liquid.tiles, std::size_t(pixelTilesAcross(scene.camera.width)) *
                                                std::size_t(pixelTilesDown(scene.camera.height)));
  EXPECT_LE(liquidTiles.stats.liquid.tilesShaded, liquidTiles.stats.liquid.tiles);
  EXPECT_GE(liquidTiles.layers.size(), 10u);
  expectSameLayers(everyPixel, liquidTiles);
  return liquidTiles;
}

std::size_t passSamples(const RenderResult& result, const char* name) {
  for (const PassTiming& pass : result.stats.passes)
    if (pass.name == name) return std::size_t(pass.samplesPassed);
  return 0;
}

}  // namespace

TEST(GLPixelTiles, ASmallBodyInACornerOfAnOddSizedFrame) {
  // 150 × 101 pixels: the last column and row of tiles are cut by the frame's edge; the body reaches it.
  const Scene scene = sceneOfSize(150, 101, {0, -3, 0.5f}, {0.55f, 0, 0.45f});
  const RenderResult result =
      expectSameBothWays(scene, particlesOf(block({0.6f, -0.1f, 0.3f}, {1.0f, 0.1f, 0.6f}, 0.05f), 0.05f));
  const std::size_t shaded = result.stats.liquid.tilesShaded;
  EXPECT_GT(shaded, 0u);
  EXPECT_LT(shaded, result.stats.liquid.tiles / 2) << "the body covers a corner, not the frame";
  // The refraction shades the marked tiles twice (its packing and itself), less what the frame's edge cuts.
  EXPECT_LE(passSamples(result, "refraction"), 2 * shaded * kPixelTileSize * kPixelTileSize);
  EXPECT_LT(passSamples(result, "refraction"), 150u * 101u);
}

TEST(GLPixelTiles, SplashesAndASheet) {
  Particles particles = wavySheet(3, 5);
  for (int i = 0; i < 12; ++i)  // lone drops above the sheet: splashes
    particles.append({0.1f * i - 0.5f, 0.0f, 0.3f + 0.02f * i}, 0.02f, ParticleKind::Liquid, 0.0f,
                     glm::vec3(0.0f));
  const RenderResult result =
      expectSameBothWays(sceneOfSize(128, 96, {0, -1.6f, 0.9f}, {0, 0, 0.1f}), particles);
  EXPECT_GT(result.stats.liquid.splashParticles, 0u);
  EXPECT_GT(result.stats.liquid.tilesShaded, 0u);
}

TEST(GLPixelTiles, TheCameraUnderWaterShadesEveryPixel) {
  // From inside the body every pixel is liquid: the refraction shades the whole frame, as without tiles.
  const Scene scene = sceneOfSize(96, 72, {0, 0, 0}, {0, 1, 0});
  const RenderResult result =
      expectSameBothWays(scene, particlesOf(block({-1, -1, -1}, {1, 1, 0.5f}, 0.05f), 0.05f));
  EXPECT_TRUE(result.stats.liquid.cameraInLiquid);
  EXPECT_EQ(passSamples(result, "refraction"), 2u * 96u * 72u);
}

TEST(GLPixelTiles, FoamOverAndUnderASheet) {
  // Spray above a sheet and bubbles under it, in a few tiles; the shadow and irradiance estimated per pixel
  // and per block of 2 (foam.occlusion_block), both upsampled and blurred in the foam's tiles only.
  Particles particles = wavySheet(3, 7);
  std::mt19937 random(3);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 offset(0.08f * unit(random), 0.08f * unit(random), 0.04f * unit(random));
    particles.append(glm::vec3(0.2f, 0.0f, 0.25f) + offset, 0.006f, ParticleKind::Spray, 0.0f,
                     glm::vec3(0.0f));
    particles.append(glm::vec3(-0.2f, 0.0f, -0.05f) + offset, 0.006f, ParticleKind::Bubble, 0.0f,
                     glm::vec3(0.0f));
  }
  for (int block : {1, 2}) {
    SCOPED_TRACE(block);
    Scene scene = sceneOfSize(128, 96, {0, -1.6f, 0.9f}, {0, 0, 0.1f});
    scene.parameters.foam.occlusion_block = block;
    const RenderResult result = expectSameBothWays(scene, particles);
    EXPECT_GT(result.stats.foam.foamPixels, 20u);
    EXPECT_GT(result.stats.foam.tilesShaded, 0u);
    EXPECT_LT(result.stats.foam.tilesShaded, result.stats.foam.tiles / 2);
  }
}

TEST(GLPixelTiles, LiquidInTheLastTilesOfAFrameTheirCentresMiss) {
  // 150 × 100 pixels: the last column of tiles holds 6 pixels and the last row 4, so those tiles' centres lie
  // outside the frame (a point whose centre leaves the viewport is clipped whole); liquid fills them.
  const Scene scene = sceneOfSize(150, 100, {0, -3, 0.5f}, {0, 0, 0.5f});
  const RenderResult result = expectSameBothWays(scene, fillingTheView(scene.camera));
  EXPECT_EQ(result.stats.liquid.tilesShaded, result.stats.liquid.tiles);
}
