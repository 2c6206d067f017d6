// Shading only the pixel tiles where the lights change the background (light.skip_unlit_tiles,
// shaders/lit_tiles.comp) changes no value of any layer: every case is rendered both ways, each renderer
// having drawn a frame with liquid over the whole view first (whose values the tiles not shaded must not
// keep), and compared bit for bit. GL tests on llvmpipe, on FloorLightScenes.h's floor.
#include <gtest/gtest.h>

#include <string>

#include <glm/geometric.hpp>

#include "FloorLightScenes.h"
#include "LiquidTestScenes.h"
#include "TempDirectory.h"
#include "framedata/PixelTiles.h"

using namespace spindrift;
using namespace liquid_test;
using namespace floor_light;

namespace {

// A block of water standing in one corner of the floor: its shadow, caustics and the sky light it takes from
// the floor around it cover part of the view.
Particles cornerBlock() {
  return slabParticles({-2.4f, -1.7f, 0.05f}, {-1.9f, -1.2f, 0.45f});
}

// Both ways, on renderers of their own, the tiled one last; returns the tiled frame.
RenderResult expectSameBothWays(Scene scene, const Particles& particles) {
  static Renderer everyPixelRenderer, tiledRenderer;
  const Particles wholeView = slabParticles({-3.0f, -2.3f, 0.05f}, {3.0f, 2.3f, 0.3f});
  everyPixelRenderer.renderParticles(scene, wholeView, 1);
  tiledRenderer.renderParticles(scene, wholeView, 1);
  scene.parameters.light.skip_unlit_tiles = false;
  const RenderResult everyPixel = everyPixelRenderer.renderParticles(scene, particles, 1);
  scene.parameters.light.skip_unlit_tiles = true;
  const RenderResult tiled = tiledRenderer.renderParticles(scene, particles, 1);
  expectAllChannelsFinite(tiled);
  EXPECT_EQ(everyPixel.stats.light.tiles, 0u) << "off: no tiles";
  EXPECT_TRUE(skipped(everyPixel, "lit_tiles"));
  EXPECT_FALSE(skipped(tiled, "lit_tiles"));
  EXPECT_EQ(tiled.stats.light.tiles,
            std::size_t(pixelTilesAcross(kWidth)) * std::size_t(pixelTilesDown(kHeight)));
  EXPECT_GT(tiled.stats.light.tilesShaded, 0u);
  expectSameLayers(everyPixel, tiled);
  return tiled;
}

}  // namespace

// One sun with its caustics: the lit background finds its shadow itself, and most of the floor is left as it
// is.
TEST(GLLitTiles, OneSunShadesOnlyTheTilesItChanges) {
  TempDirectory directory;
  Scene scene = floorScene(directory);
  scene.lights.push_back(sunAlong({0.5f, 0.2f, -1.0f}));
  const RenderResult tiled = expectSameBothWays(scene, cornerBlock());
  EXPECT_LT(tiled.stats.light.tilesShaded, tiled.stats.light.tiles / 2);
  // The tiles left as they are hold the background and the neutral light layers.
  EXPECT_FLOAT_EQ(at(*tiled.layer("liquid_shadow"), kWidth, kWidth - 1, 0, 0), 1.0f);
  EXPECT_FLOAT_EQ(at(*tiled.layer("caustics"), kWidth, kWidth - 1, 0, 0), 0.0f);
  EXPECT_FLOAT_EQ(at(*tiled.layer("liquid_sky"), kWidth, kWidth - 1, 0, 0), 1.0f);
}

// Two suns, or one without caustics, go through the shadow pass's sums.
TEST(GLLitTiles, TheShadowPassSumsAreTiledAlike) {
  TempDirectory directory;
  Scene scene = floorScene(directory);
  scene.lights.push_back(sunAlong({0.5f, 0.2f, -1.0f}));
  scene.lights.push_back(sunAlong({-0.3f, 0.4f, -1.0f}, 1.5f));
  {
    SCOPED_TRACE("two suns");
    const RenderResult tiled = expectSameBothWays(scene, cornerBlock());
    EXPECT_FALSE(skipped(tiled, "liquid_shadow"));
  }
  scene.lights.pop_back();
  scene.parameters.light.caustics = false;
  SCOPED_TRACE("one sun, no caustics");
  expectSameBothWays(scene, cornerBlock());
}

// The background's own light passes (Cycles'), and without them any light.direct_fraction: the tiles left as
// they are get the background to the bit whatever the fraction (lit_background.frag's arithmetic).
TEST(GLLitTiles, LightPassesAndDirectFractionsLeaveTheBackgroundExact) {
  TempDirectory directory;
  Scene scene = floorScene(directory);
  scene.lights.push_back(sunAlong({0.5f, 0.2f, -1.0f}));
  for (float fraction : {0.1f, 0.3f, 0.6f, 1.0f}) {
    SCOPED_TRACE(fraction);
    scene.parameters.light.direct_fraction = fraction;
    expectSameBothWays(scene, cornerBlock());
  }
  const float passes[6][3] = {{0.8f, 0.7f, 0.6f},    {0.2f, 0.25f, 0.3f},   {0.6f, 0.5f, 0.4f},
                              {0.05f, 0.05f, 0.05f}, {0.02f, 0.02f, 0.03f}, {0.5f, 0.5f, 0.5f}};
  writeFloorWithLightPasses(scene.background.image, kCameraHeight, passes);
  SCOPED_TRACE("Cycles' light passes");
  expectSameBothWays(scene, cornerBlock());
}

// A spot light aimed at the block, and a point light beside it (shadow only).
TEST(GLLitTiles, SpotAndPointLightsAreTiledAlike) {
  TempDirectory directory;
  Scene scene = floorScene(directory);
  Light spot;
  spot.type = Light::Type::Spot;
  spot.position = {-1.0f, -0.5f, 2.5f};
  spot.direction = glm::normalize(glm::vec3(-1.15f, -0.95f, -2.25f));
  spot.spotAngleDegrees = 50.0f;
  spot.strength = 400.0f;
  scene.lights.push_back(spot);
  {
    SCOPED_TRACE("spot");
    expectSameBothWays(scene, cornerBlock());
  }
  scene.lights.front().type = Light::Type::Point;
  SCOPED_TRACE("point");
  expectSameBothWays(scene, cornerBlock());
}

// A floating slab under a low sun casts its shadow away from itself, where no sky light is taken (one sky
// direction, about straight up): those tiles are lit by the shadow alone, found from the light's columns
// (caustics on) or the shadow pass's sums (off). In a view of 32 texels a tile falls in few enough of the
// light's columns that they are read instead of its pixels (lit_tiles.comp, shadowPossible).
TEST(GLLitTiles, AShadowAwayFromItsLiquidIsShaded) {
  TempDirectory directory;
  Scene scene = floorScene(directory);
  scene.lights.push_back(sunAlong({0.9f, 0.0f, -1.0f}));
  scene.parameters.light.sky_occlusion_directions = 1;
  const Particles floating = slabParticles({-2.6f, -0.4f, 0.8f}, {-2.0f, 0.4f, 2.0f});
  for (int viewSize : {512, 32})
    for (bool caustics : {true, false}) {
      SCOPED_TRACE(std::to_string(viewSize) + (caustics ? " texels, caustics" : " texels, no caustics"));
      scene.parameters.light.shadow_map_size = viewSize;
      scene.parameters.light.caustics = caustics;
      const RenderResult tiled = expectSameBothWays(scene, floating);
      EXPECT_LT(tiled.stats.light.tilesShaded, tiled.stats.light.tiles / 2);
      int shadowed = 0;
      for (int row = 0; row < kHeight; ++row)
        for (int column = 0; column < kWidth; ++column)
          shadowed += at(*tiled.layer("liquid_shadow"), kWidth, column, row, 0) < 0.99f;
      EXPECT_GT(shadowed, 100);
    }
}
