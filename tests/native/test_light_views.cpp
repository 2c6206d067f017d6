#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "prep/LightViews.h"

namespace spindrift {
namespace {

constexpr float kRadius = 0.02f;

// A sheet of liquid 3 m across and 5 particles thick, 1.2 radii apart: the bounds span ~3 m, 75 radii
// each side of the centre, so a view of a particle radius per half texel is far finer than 128 texels.
Particles sheet() {
  Particles particles;
  const float spacing = 1.2f * kRadius;
  const int across = int(3.0f / spacing);
  for (int i = 0; i < across; ++i)
    for (int j = 0; j < across; ++j)
      for (int k = 0; k < 5; ++k)
        particles.append({float(i) * spacing - 1.5f, float(j) * spacing - 1.5f, float(k) * spacing}, kRadius,
                         ParticleKind::Liquid, 0.0f, {});
  return particles;
}

// A camera whose pixels at the liquid (2.6 mm) are finer than any detail the rule asks for: the detail
// decides.
Camera distantCamera() {
  return Camera::lookAt(512, 512, 1.0f, {0, -40, 10}, {0, 0, 0}, {0, 0, 1});
}

float texelOf(const LiquidBounds& bounds, int side) {
  return 2.04f * bounds.radius / float(side);
}

TEST(LightViews, PlainParticlesGetLightTexelsPerParticleRadius) {
  LiquidParameters liquid;
  const LiquidBounds bounds = liquidBounds(sheet(), liquid);
  EXPECT_FLOAT_EQ(bounds.detailRadius, kRadius);
  LightParameters light;
  const int side = lightViewSize(bounds, distantCamera(), light);
  ASSERT_LT(side, light.shadow_map_size);
  EXPECT_NEAR(texelOf(bounds, side), kRadius / light.texels_per_radius, 0.01f * kRadius);
}

// Mantaflow's mesh averages the particles over its kernel radius r_m, so the surface the user's render shows
// has no bump smaller than r_m: a view resolves r_m, not the particle radius, and is r_m / r times coarser.
TEST(LightViews, MantaflowSurfaceGetsLightTexelsPerKernelRadius) {
  LiquidParameters liquid;
  liquid.mesh_kernel_radius = 2.5f;
  const LiquidBounds bounds = liquidBounds(sheet(), liquid);
  EXPECT_FLOAT_EQ(bounds.detailRadius, 2.5f * kRadius);
  LightParameters light;
  const int side = lightViewSize(bounds, distantCamera(), light);
  EXPECT_NEAR(texelOf(bounds, side), 2.5f * kRadius / light.texels_per_radius, 0.025f * kRadius);
  // Never coarser than 128 texels across (a body of a few large particles curves at its own size).
  liquid.mesh_kernel_radius = 40.0f;
  EXPECT_EQ(lightViewSize(liquidBounds(sheet(), liquid), distantCamera(), light), 128);
  // A kernel below the particle radius does not make the view finer than the particles' own detail.
  liquid.mesh_kernel_radius = 0.5f;
  EXPECT_FLOAT_EQ(liquidBounds(sheet(), liquid).detailRadius, kRadius);
}

// Whether two views hold the same ellipsoids, bit for bit, in the same order, seen by the same camera.
bool sameView(const LightPreparation& a, const LightPreparation& b) {
  const std::vector<EllipsoidInstance>&x = a.liquid.aggregates, &y = b.liquid.aggregates;
  return a.view.camera.width == b.view.camera.width &&
         a.view.camera.worldFromCamera == b.view.camera.worldFromCamera && a.leftOut == b.leftOut &&
         x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(EllipsoidInstance)) == 0;
}

bool samePreparation(const LightingPreparation& a, const LightingPreparation& b) {
  if (a.lights.size() != b.lights.size() || a.viewSize != b.viewSize || !a.sky || !b.sky) return false;
  for (std::size_t i = 0; i < a.lights.size(); ++i)
    if (!sameView(a.lights[i], b.lights[i])) return false;
  return sameView(*a.sky, *b.sky);
}

// The sky occlusion's samples stand for as many pixels as span six detail radii where the camera sees the
// liquid's centre, within [4, 8]: a near camera's 8, a far one's 4, and between them the pixels that fit.
TEST(LightViews, SkyOcclusionSamplesSpanSixDetailRadiiWithinFourToEightPixels) {
  LiquidParameters liquid;
  const LiquidBounds bounds = liquidBounds(sheet(), liquid);
  const auto cameraAt = [](float distance) {
    return Camera::lookAt(480, 270, 40.0f, {0.0f, -distance, 0.0f}, {0.0f, 0.0f, 0.0f}, {0, 0, 1});
  };
  EXPECT_EQ(skyOcclusionScale(bounds, cameraAt(1.0f)), 8);
  EXPECT_EQ(skyOcclusionScale(bounds, cameraAt(100.0f)), 4);
  // Six radii over 5.5 of its pixels there.
  const float distance = 6.0f * kRadius / 5.5f / cameraAt(1.0f).pixelSizeAt(1.0f);
  EXPECT_EQ(skyOcclusionScale(bounds, cameraAt(distance)), 5);
  // Degenerate: no liquid, a camera at the liquid's centre, a NaN position.
  EXPECT_EQ(skyOcclusionScale(LiquidBounds{}, cameraAt(1.0f)), 4);
  const Camera inside =
      Camera::lookAt(480, 270, 40.0f, bounds.centre, bounds.centre + glm::vec3(0, 1, 0), {0, 0, 1});
  EXPECT_EQ(skyOcclusionScale(bounds, inside), 8);
  EXPECT_EQ(skyOcclusionScale(bounds, cameraAt(std::nanf(""))), 4);
}

// A camera orbiting a paused frame keeps the lights' views; a moved light, other particles or a camera so far
// that it wants coarser views prepare them anew, and whatever is kept is what a fresh preparation gives.
TEST(LightViews, ViewsAreKeptWhileParticlesLightsAndViewSidesStayTheSame) {
  const Particles particles = sheet();
  Parameters parameters;
  Light sun;
  sun.direction = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
  std::vector<Light> lights = {sun};
  const Camera orbited = Camera::lookAt(512, 512, 1.0f, {30, -30, 12}, {0, 0, 0}, {0, 0, 1});
  const Camera farAway = Camera::lookAt(64, 64, 60.0f, {0, -400, 100}, {0, 0, 0}, {0, 0, 1});
  LightingAcrossFrames across;
  const auto expectFrame = [&](const Camera& camera, bool sameParticles, bool kept) {
    const LightingPreparation& prepared =
        across.forFrame(particles, camera, lights, false, parameters, nullptr, sameParticles);
    EXPECT_EQ(across.kept(), kept);
    EXPECT_TRUE(samePreparation(prepared, prepareLighting(particles, camera, lights, false, parameters)));
  };
  expectFrame(distantCamera(), false, false);
  expectFrame(orbited, true, true);
  expectFrame(orbited, false, false);  // other particles
  lights[0].direction = glm::normalize(glm::vec3(-0.3f, 0.2f, -1.0f));
  expectFrame(orbited, true, false);
  expectFrame(distantCamera(), true, true);
  ASSERT_NE(lightViewSize(liquidBounds(particles, parameters.liquid), farAway, parameters.light),
            lightViewSize(liquidBounds(particles, parameters.liquid), orbited, parameters.light));
  expectFrame(farAway, true, false);
  parameters.light.texels_per_radius = 1.5f;
  expectFrame(farAway, true, false);
}

// The frame is planned before the lights' views are prepared (they are prepared while the GL thread draws the
// camera's surface): the count found from the bounds alone is the one the preparation then finds.
TEST(LightViews, TheLightsSeeingTheLiquidAreCountedAsThePreparationFindsThem) {
  Particles particles;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 3; ++k)
        particles.append({0.1f * float(i), 0.1f * float(j), 0.1f * float(k)}, 0.06f, ParticleKind::Liquid,
                         0.0f, {});
  Parameters parameters;
  Light sun;
  Light distantPoint;
  distantPoint.type = Light::Type::Point;
  distantPoint.position = {0.5f, 0.5f, 10.0f};
  Light pointInside = distantPoint;
  pointInside.position = {0.45f, 0.45f, 0.1f};
  Light spotAtIt;
  spotAtIt.type = Light::Type::Spot;
  spotAtIt.position = {0.5f, 0.5f, 6.0f};
  spotAtIt.direction = {0.0f, 0.0f, -1.0f};
  Light spotAway = spotAtIt;
  spotAway.direction = {0.0f, 0.0f, 1.0f};
  const std::vector<Light> lights = {sun, distantPoint, pointInside, spotAtIt, spotAway};
  const LightsSeeing seeing = lightsSeeingTheLiquid(particles, lights, parameters.liquid);
  EXPECT_EQ(seeing.lights, 3u);
  EXPECT_EQ(seeing.causticLights, 2u);
  const LightingPreparation prepared = prepareLighting(particles, distantCamera(), lights, false, parameters);
  EXPECT_EQ(seeing.lights, prepared.lights.size());
  EXPECT_EQ(seeing.causticLights, causticLights(prepared));
  EXPECT_EQ(prepared.skipped.size(), 2u);
  // No liquid, or no light: none.
  EXPECT_EQ(lightsSeeingTheLiquid(Particles{}, lights, parameters.liquid).lights, 0u);
  EXPECT_EQ(lightsSeeingTheLiquid(particles, {}, parameters.liquid).lights, 0u);
}

// A scene lit by its world alone: no light's view, the sky's view all the same, as the lamps' frames have it;
// without the world's light, nothing at all.
TEST(LightViews, TheWorldAloneHasTheSkysViewAndNoLightsView) {
  Particles particles;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      particles.append({0.1f * float(i), 0.1f * float(j), 0.0f}, 0.06f, ParticleKind::Liquid, 0.0f, {});
  const Parameters parameters;
  const LightingPreparation alone = prepareLighting(particles, distantCamera(), {}, true, parameters);
  EXPECT_TRUE(alone.lights.empty());
  ASSERT_TRUE(alone.sky.has_value());
  EXPECT_TRUE(alone.sky->view.sky);
  const LightingPreparation withSun =
      prepareLighting(particles, distantCamera(), {Light{}}, false, parameters);
  ASSERT_TRUE(withSun.sky.has_value());
  EXPECT_EQ(alone.sky->view.camera.width, withSun.sky->view.camera.width);
  EXPECT_EQ(alone.sky->liquid.aggregates.size(), withSun.sky->liquid.aggregates.size());
  EXPECT_FALSE(prepareLighting(particles, distantCamera(), {}, false, parameters).sky.has_value());
  EXPECT_FALSE(prepareLighting(Particles{}, distantCamera(), {}, true, parameters).sky.has_value());
}

}  // namespace
}  // namespace spindrift
