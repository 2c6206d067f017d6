// The CPU side of foam.cull_hidden (prep/HiddenFoam.cpp), without a GPU: which particles the tiles' depths
// hide, checked against the sprites' footprints worked out by hand for a camera looking straight down.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/trigonometric.hpp>

#include "prep/HiddenFoam.h"

using namespace spindrift;

namespace {

// 64 x 64 pixels, 8 x 8 tiles of 8 pixels, looking down -Z from z = 10 with a 90 degree field of view: a
// point at eye depth d and world (x, y) lands on window x = 32 + 32 x / d (the same for y).
const Camera kCamera = Camera::lookAt(64, 64, 90.0f, {0, 0, 10}, {0, 0, 0}, {0, 1, 0});

FoamVisibilityTiles tilesHiddenBeyond(float solids, float solidsOrLiquid) {
  FoamVisibilityTiles tiles;
  tiles.columns = tiles.rows = 8;
  tiles.hiddenBeyond.assign(64, glm::vec2(solids, solidsOrLiquid));
  return tiles;
}

FoamInstance particleAt(float x, float y, float depth, float radius, int type = 0) {
  return {glm::vec4(x, y, 10.0f - depth, radius), glm::vec4(float(type), 0.0f, 0.0f, 0.0f)};
}

}  // namespace

TEST(HiddenFoam, ParticlesWhollyBeyondTheTilesAreLeftOutByWhatHidesThem) {
  FoamVisibilityTiles tiles = tilesHiddenBeyond(8.0f, 6.0f);
  const std::vector<FoamInstance> particles = {
      particleAt(0.0f, 0.0f, 9.0f, 0.5f, 0),      // nearest 8.5: behind the solids
      particleAt(1.0f, 1.0f, 7.0f, 0.5f, 1),      // nearest 6.5: under the liquid
      particleAt(-1.0f, 0.0f, 6.4f, 0.5f, 2),     // nearest 5.9: shows
      particleAt(2.0f, -2.0f, 6.5003f, 0.5f, 0),  // nearest 6.0003: within the margin, kept
  };
  const VisibleFoam visible = cullHiddenFoam(particles, kCamera, tiles);
  EXPECT_EQ(visible.behindSolids, 1u);
  EXPECT_EQ(visible.underLiquid, 1u);
  ASSERT_EQ(visible.instances.size(), 2u);
  // In their order: the sprite passes draw the survivors as they would have drawn all.
  EXPECT_EQ(visible.instances[0].typeAndAge.x, 2.0f);
  EXPECT_EQ(visible.instances[1].centreAndRadius.x, 2.0f);
}

TEST(HiddenFoam, ATileThatShowsFoamKeepsEverySpriteThatReachesIt) {
  FoamVisibilityTiles tiles = tilesHiddenBeyond(5.0f, 5.0f);
  // Tile (5, 4), window x 40-48, y 32-40, shows everything.
  tiles.hiddenBeyond[4 * 8 + 5] = glm::vec2(1e10f);
  // At eye depth 8, world x maps to window 32 + 4 x: a sprite of radius 0.25 centred on x covers
  // [32 + 4 (x - 0.25), 32 + 4 (x + 0.25)].
  const std::vector<FoamInstance> particles = {
      particleAt(1.5f, 1.0f, 8.0f, 0.25f),   // window x 37-39: stays in tile 4, hidden
      particleAt(1.9f, 1.0f, 8.0f, 0.25f),   // window x 38.6-40.6: reaches tile 5, kept
      particleAt(3.5f, 1.0f, 8.0f, 0.25f),   // window x 45-47, inside tile 5, kept
      particleAt(3.5f, -1.0f, 8.0f, 0.25f),  // window y 27-29: tile row 3, hidden
  };
  const VisibleFoam visible = cullHiddenFoam(particles, kCamera, tiles);
  EXPECT_EQ(visible.behindSolids, 2u);
  EXPECT_EQ(visible.instances.size(), 2u);
}

TEST(HiddenFoam, LargeSpritesAndSpritesAtTheNearPlaneAreDrawn) {
  const FoamVisibilityTiles tiles = tilesHiddenBeyond(1.0f, 1.0f);
  const std::vector<FoamInstance> particles = {
      particleAt(0.0f, 0.0f, 4.0f, 2.0f),   // window 16-48 on each axis: 25 tiles, drawn untested
      particleAt(0.0f, 0.0f, 3.0f, 0.2f),   // small and hidden
      particleAt(0.0f, 0.0f, 0.05f, 0.1f),  // reaches behind the near plane: drawn as before
  };
  const VisibleFoam visible = cullHiddenFoam(particles, kCamera, tiles);
  EXPECT_EQ(visible.behindSolids, 1u);
  EXPECT_EQ(visible.instances.size(), 2u);
}

TEST(HiddenFoam, NanTilesAndNoTilesHideNothing) {
  FoamVisibilityTiles tiles = tilesHiddenBeyond(std::nanf(""), std::nanf(""));
  const std::vector<FoamInstance> particles = {particleAt(0.0f, 0.0f, 9.0f, 0.5f)};
  EXPECT_EQ(cullHiddenFoam(particles, kCamera, tiles).instances.size(), 1u);
  EXPECT_TRUE(cullHiddenFoam({}, kCamera, tiles).instances.empty());
}
