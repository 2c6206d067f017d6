// Paths through the liquid that go on behind a solid (docs/liquid.md, "Where the light goes missing"): a pool
// in a tank seen over the tank's near wall. The light refracted at the water's surface travels down, and on
// the screen the wall stands in front of the rest of its path: the wall hides the water there, so the screen
// holds neither where the path ends nor what it meets. Such a path ends on a submerged surface, never on the
// wall's outside, which faces the camera from in front of the water.
#include <gtest/gtest.h>

#include <cmath>

#include "BackgroundFiles.h"
#include "LiquidTestScenes.h"
#include "TempDirectory.h"

using namespace spindrift;
using namespace liquid_test;

namespace {

constexpr int kWidth = 160, kHeight = 120;
constexpr float kWallX = 1.1f;    // the tank's near wall: the plane x = 1.1 from the floor up to kWallTop
constexpr float kWallTop = 0.6f;  // the water stands at 0.4 (a lattice up to 0.35, radius 0.05)
const glm::vec3 kWallColour{1, 0, 0};   // red outside
const glm::vec3 kFloorColour{0, 1, 0};  // the tank's floor, and the ground beyond, green

// Eye depth of the first solid each pixel's centre ray meets: the wall where the ray crosses x = kWallX below
// its top (when there is a wall), else the floor (z = 0); and whether it is the wall.
std::pair<float, bool> solidAt(const Camera& camera, int column, int row, bool wall = true) {
  const glm::vec3 eye = camera.position();
  const glm::vec3 step =
      camera.worldFromPixelAndDepth({column + 0.5f, row + 0.5f}, 1.0f) - eye;  // per unit depth
  if (wall && step.x < 0.0f) {
    const float depth = (kWallX - eye.x) / step.x;
    const float height = eye.z + depth * step.z;
    if (depth > 0.0f && height >= 0.0f && height <= kWallTop) return {depth, true};
  }
  return {step.z < 0.0f ? -eye.z / step.z : 1e4f, false};
}

Scene tankScene(const TempDirectory& directory, bool wall) {
  Scene scene;
  scene.camera = Camera::lookAt(kWidth, kHeight, 40.0f, {4.0f, 0.0f, 2.0f}, {0.0f, 0.0f, 0.2f}, {0, 0, 1});
  scene.background.color = glm::vec3(0.0f);  // the sky the surface reflects: nothing
  scene.background.image = directory.path() / "tank.exr";
  const Camera camera = scene.camera;
  writeBackgroundExr(
      scene.background.image, kWidth, kHeight,
      [&](int column, int row) {
        return solidAt(camera, column, row, wall).second ? kWallColour : kFloorColour;
      },
      [&](int column, int row) { return solidAt(camera, column, row, wall).first; });
  return scene;
}

Particles pool() {
  return particlesOf(block({-1.0f, -1.0f, 0.05f}, {1.0f, 1.0f, 0.35f}, 0.05f), 0.05f);
}

}  // namespace

// Over the wall the camera sees the water's surface; light refracted there goes down behind the wall. No
// liquid pixel's refracted light may be the wall's red, and every one that reads the background reads a floor
// texel.
TEST(GLLiquidHiddenPaths, APathBehindATanksWallEndsOnTheSubmergedFloorNotOnTheWall) {
  TempDirectory directory;
  Scene scene = tankScene(directory, true);
  scene.parameters.liquid.absorption_rgb = {0.0f, 0.0f, 0.0f};  // so the floor's green is not absorbed away
  // The pool as Yu and Turk shape it, its faces about 0.4 r beyond the particles. Grown to the particles'
  // radius (liquid.reach_radius), 3 of its 600-odd paths, at the pool's two ends, leave through its end faces
  // (this tank has no side walls) into the air behind the near wall and read the wall where they pass behind
  // it: a path in air that passes behind a solid is not one this test is about (docs/liquid.md, "Particles
  // reach their radius").
  scene.parameters.liquid.reach_radius = false;
  // Likewise the paths that total internal reflection carries on to those end faces: with 4 reflections
  // besides the refractions (liquid.internal_reflections' default), 4 paths at the pool's two ends get there
  // and read the wall; with the 4 crossings in all of before, none did.
  scene.parameters.liquid.internal_reflections = 0;
  // And the particles as given: relaxed (liquid.relax_surface), those beside the pool's top edges rise by up
  // to a tenth of a spacing, and one path at its end leaves through an end face the same way.
  scene.parameters.liquid.relax_surface = false;
  const RenderResult result = renderer().renderParticles(scene, pool(), 1);
  expectAllChannelsFinite(result);
  EXPECT_GT(result.stats.liquid.exitsBehindSolids, 100u)
      << "no path went behind the wall: the scene is wrong";

  int liquidPixels = 0, readsBackground = 0;
  for (int row = 0; row < kHeight; ++row)
    for (int column = 0; column < kWidth; ++column) {
      if (at(*result.layer("liquid"), kWidth, column, row, 3) <= 0.0f) continue;
      ++liquidPixels;
      // The refracted light (all but what the surface reflects: the water's rounded near edge does reflect
      // the wall, as it should).
      const float refracted = at(*result.layer("liquid"), kWidth, column, row, 0) -
                              at(*result.layer("reflection"), kWidth, column, row, 0);
      EXPECT_LT(refracted, 1e-3f) << column << ", " << row;
      if (at(*result.layer("refraction_uv"), kWidth, column, row, 2) <= 0.0f) continue;
      ++readsBackground;
      // refraction_uv is (0, 0) at the bottom left; rows of the layers count from the top.
      const int lookedUpColumn = int(at(*result.layer("refraction_uv"), kWidth, column, row, 0) * kWidth);
      const int lookedUpRow =
          kHeight - 1 - int(at(*result.layer("refraction_uv"), kWidth, column, row, 1) * kHeight);
      EXPECT_FALSE(solidAt(scene.camera, lookedUpColumn, lookedUpRow).second)
          << column << ", " << row << " looks up the wall at " << lookedUpColumn << ", " << lookedUpRow;
    }
  EXPECT_GT(liquidPixels, 500);
  EXPECT_GT(readsBackground, liquidPixels / 2);
}

// Without the wall nothing hides the water: no path is counted as hidden.
TEST(GLLiquidHiddenPaths, WithoutAWallNoPathIsHidden) {
  TempDirectory directory;
  const Scene scene = tankScene(directory, false);
  const RenderResult result = renderer().renderParticles(scene, pool(), 1);
  expectAllChannelsFinite(result);
  EXPECT_EQ(result.stats.liquid.exitsBehindSolids, 0u);
  EXPECT_GT(result.stats.liquid.liquidPixels, 500u);
}
