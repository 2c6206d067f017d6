// The foam's CPU preparation: which sprites are too small to hold a pixel's centre (foam.cull_sub_pixel),
// against a brute-force search of the pixel centres around each, and the counts prepareFoam reports.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "prep/FoamPreparation.h"

using namespace spindrift;

namespace {

// Whether any pixel centre (i + 0.5, j + 0.5) within three pixels of the centre lies inside the ellipse
// itself, not grown: the fragments the sprite passes rasterise, by exhaustive search.
bool anyCentreInside(const glm::vec2& centre, const glm::vec2& radii) {
  for (int j = int(std::floor(centre.y)) - 3; j <= int(std::floor(centre.y)) + 3; ++j)
    for (int i = int(std::floor(centre.x)) - 3; i <= int(std::floor(centre.x)) + 3; ++i) {
      const glm::vec2 offset = (glm::vec2(float(i) + 0.5f, float(j) + 0.5f) - centre) / radii;
      if (offset.x * offset.x + offset.y * offset.y <= 1.0f) return true;
    }
  return false;
}

}  // namespace

TEST(FoamSubPixel, DiscOnAPixelCentreHoldsIt) {
  EXPECT_TRUE(foamSpriteHoldsAPixelCentre({10.5f, 7.5f}, {0.01f, 0.01f}));
}

TEST(FoamSubPixel, SmallDiscOnAPixelCornerHoldsNone) {
  // The nearest centres lie half a pixel's diagonal (0.707) away.
  EXPECT_FALSE(foamSpriteHoldsAPixelCentre({10.0f, 7.0f}, {0.6f, 0.6f}));
  EXPECT_TRUE(foamSpriteHoldsAPixelCentre({10.0f, 7.0f}, {0.72f, 0.72f}));
}

TEST(FoamSubPixel, DiscJustShortOfACentreCountsAsHoldingIt) {
  // 0.5 px from the nearest centre: a radius 0.5 % short is inside the 1 % margin, 5 % short is not.
  EXPECT_TRUE(foamSpriteHoldsAPixelCentre({10.0f, 7.5f}, {0.4975f, 0.4975f}));
  EXPECT_FALSE(foamSpriteHoldsAPixelCentre({10.0f, 7.5f}, {0.475f, 0.475f}));
}

TEST(FoamSubPixel, ThinEllipseAlongARowOfCentres) {
  // Between two rows of centres, reaching neither along y, but a centre along x.
  EXPECT_FALSE(foamSpriteHoldsAPixelCentre({10.0f, 7.0f}, {0.9f, 0.3f}));
  EXPECT_TRUE(foamSpriteHoldsAPixelCentre({10.0f, 7.5f}, {0.9f, 0.3f}));
}

TEST(FoamSubPixel, WideSpritesAndNegativeWindowCoordinatesAreKept) {
  EXPECT_TRUE(foamSpriteHoldsAPixelCentre({10.0f, 7.0f}, {3.0f, 0.2f}));
  EXPECT_TRUE(foamSpriteHoldsAPixelCentre({-0.5f, -3.5f}, {0.1f, 0.1f}));
  EXPECT_FALSE(foamSpriteHoldsAPixelCentre({-1.0f, -4.0f}, {0.3f, 0.3f}));
}

TEST(FoamSubPixel, NaNAndInfiniteInputsAreKeptForTheShadersToReject) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  // Kept: what a sprite with such a position draws is the shaders' to decide, as without the test.
  EXPECT_TRUE(foamSpriteHoldsAPixelCentre({10.0f, 7.0f}, {nan, 0.3f}));
  EXPECT_TRUE(foamSpriteHoldsAPixelCentre({10.0f, 7.0f}, {inf, inf}));
  EXPECT_TRUE(foamSpriteHoldsAPixelCentre({nan, 7.0f}, {0.3f, 0.3f}));
}

// Never a sprite left out that holds a centre; and of those under 0.9 px across both axes that hold none,
// nearly all left out (the rest are within the 1 % margin).
TEST(FoamSubPixel, AgreesWithAnExhaustiveSearchOfPixelCentres) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> position(-20.0f, 20.0f), radius(0.05f, 1.2f);
  int narrowHoldingNone = 0, narrowLeftOut = 0;
  for (int k = 0; k < 200000; ++k) {
    const glm::vec2 centre(position(random), position(random));
    const glm::vec2 radii(radius(random), radius(random));
    const bool inside = anyCentreInside(centre, radii);
    const bool holds = foamSpriteHoldsAPixelCentre(centre, radii);
    if (inside) ASSERT_TRUE(holds) << centre.x << ", " << centre.y << " radii " << radii.x << ", " << radii.y;
    if (radii.x < 0.9f && radii.y < 0.9f && !inside) {
      ++narrowHoldingNone;
      narrowLeftOut += !holds;
    }
  }
  EXPECT_GT(narrowHoldingNone, 20000);
  EXPECT_GT(narrowLeftOut, narrowHoldingNone * 95 / 100);
  std::printf("[ measured ] %d random sprites under 0.9 px hold no centre, %d of them left out\n",
              narrowHoldingNone, narrowLeftOut);
}

TEST(FoamSubPixel, PrepareFoamCountsTheSpritesLeftOut) {
  // 480 x 270 pixels, 50 degrees: a pixel is 0.0173 units wide at a depth of 5 units.
  const Camera camera = Camera::lookAt(480, 270, 50.0f, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  Particles particles;
  // Tiny spray over the middle of the view, and a few large surface foam particles.
  std::mt19937 random(3);
  std::uniform_real_distribution<float> position(-1.0f, 1.0f);
  for (int i = 0; i < 1000; ++i)
    particles.append({position(random), position(random), 0.0f}, 0.002f, ParticleKind::Spray, 0.0f,
                     glm::vec3(0.0f));
  for (int i = 0; i < 10; ++i)
    particles.append({position(random), position(random), 0.0f}, 0.1f, ParticleKind::Foam, 0.0f,
                     glm::vec3(0.0f));
  FoamParameters parameters;
  const FoamPreparation culled = prepareFoam(particles, camera, parameters);
  EXPECT_EQ(culled.spray, 1000u);  // in view, counted by type whether drawn or not
  EXPECT_EQ(culled.surface, 10u);
  EXPECT_GT(culled.subPixel, 900u);  // radius 0.12 px at most: about 5 % hold a centre
  EXPECT_EQ(culled.instances.size() + culled.subPixel, 1010u);
  parameters.cull_sub_pixel = false;
  const FoamPreparation drawn = prepareFoam(particles, camera, parameters);
  EXPECT_EQ(drawn.subPixel, 0u);
  EXPECT_EQ(drawn.instances.size(), 1010u);
}
