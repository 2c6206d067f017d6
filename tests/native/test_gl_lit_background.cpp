// How the liquid's shadow and caustics scale the background's light (docs/liquid.md, "Light through the
// liquid"): exactly through Cycles' light passes when the background has them, with light.direct_fraction
// when it has none, and 1 / n^2 of a submerged floor's radiance. GL tests on llvmpipe against closed forms,
// on FloorLightScenes.h's floor.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "BackgroundFiles.h"
#include "FloorLightScenes.h"
#include "LiquidTestScenes.h"
#include "OpticsReference.h"
#include "TempDirectory.h"

using namespace spindrift;
using namespace liquid_test;
using namespace floor_light;

// The shadow and caustics scale the background's direct light only: exactly through Cycles' light passes when
// the background has them, and with light.direct_fraction when it has none. Checked on the floor the slab
// shadows where the camera sees no liquid in front of it.
// Cycles counts the world's light as direct light too (DiffDir holds the sky's share as well as the lamps'):
// only the lamps' share, the light a sun of known strength gives the floor (E cos / pi), is scaled by the
// shadow and caustics; the rest is sky light, which liquid_sky scales (here the floating slab takes part of
// the floor's sky). A strong sun (share 1, clamped) and one that gives half of DiffDir.
TEST(GLLiquidLight, LitBackgroundScalesTheLampsShareOfTheDirectLight) {
  TempDirectory directory;
  const float passes[6][3] = {{0.6f, 0.5f, 0.4f}, {0.2f, 0.25f, 0.3f},   {0.7f, 0.6f, 0.5f},
                              {0.1f, 0.1f, 0.1f}, {0.05f, 0.05f, 0.05f}, {0.3f, 0.3f, 0.3f}};
  const double incidence = glm::radians(45.0);
  const double diffuseDirect = (passes[0][0] + passes[0][1] + passes[0][2]) / 3.0;
  for (const double lampShare : {1.0, 0.5}) {
    SCOPED_TRACE("lamps' share of the direct light " + std::to_string(lampShare));
    // The floor faces up: a sun of strength E gives it E cos(incidence) / pi of diffuse light.
    const float strength =
        lampShare >= 1.0 ? 3.0f : float(lampShare * diffuseDirect * glm::pi<double>() / std::cos(incidence));
    Scene scene = floorScene(directory);
    scene.background.image = directory.path() / "floor_passes.exr";
    writeFloorWithLightPasses(scene.background.image, kCameraHeight, passes);
    scene.lights.push_back(
        sunAlong({float(std::sin(incidence)), 0.0f, -float(std::cos(incidence))}, strength));
    const Particles slab = slabParticles({-1.0f, -1.0f, 1.0f}, {0.5f, 1.0f, 1.4f});
    const RenderResult withPasses = renderer().renderParticles(scene, slab, 1);
    expectAllChannelsFinite(withPasses);
    EXPECT_TRUE(withPasses.stats.light.lightPasses);

    Scene plain = floorScene(directory);
    plain.lights = scene.lights;
    const RenderResult withoutPasses = renderer().renderParticles(plain, slab, 1);
    EXPECT_FALSE(withoutPasses.stats.light.lightPasses);
    const float fraction = plain.parameters.light.direct_fraction;

    int compared = 0;
    for (int row = 0; row < kHeight; ++row)
      for (int column = 0; column < kWidth; ++column) {
        if (at(*withPasses.layer("liquid"), kWidth, column, row, 3) > 0.0f) continue;
        for (int c = 0; c < 3; ++c) {
          const double shadow = at(*withPasses.layer("liquid_shadow"), kWidth, column, row, c);
          const double caustic = at(*withPasses.layer("caustics"), kWidth, column, row, c);
          const double sky = at(*withPasses.layer("liquid_sky"), kWidth, column, row, c);
          if (c == 0 && shadow + caustic > 0.9) break;
          if (c == 0) ++compared;
          const double combined =
              passes[2][c] * (passes[0][c] + passes[1][c]) + passes[5][c] * (passes[3][c] + passes[4][c]);
          const double skyLost = (1 - lampShare) * (1 - sky);
          const double expected =
              combined - passes[2][c] * passes[0][c] * (lampShare * (1 - shadow - caustic) + skyLost) -
              passes[5][c] * passes[3][c] * (lampShare * (1 - shadow) + skyLost) -
              (passes[2][c] * passes[1][c] + passes[5][c] * passes[4][c]) * (1 - sky);
          EXPECT_NEAR(at(*withPasses.layer("composite"), kWidth, column, row, c), expected, 2e-4);
          const double plainShadow = directMultiplier(withoutPasses, column, row, c);
          const double plainSky = at(*withoutPasses.layer("liquid_sky"), kWidth, column, row, c);
          EXPECT_NEAR(at(*withoutPasses.layer("composite"), kWidth, column, row, c),
                      0.5 * (fraction * plainShadow + (1 - fraction) * plainSky), 1e-4);
        }
      }
    EXPECT_GT(compared, 40) << "shadowed floor pixels with no liquid in front";
  }
}

// Radiance divided by the square of the index is what carries across an interface, so a floor under water,
// seen from air, keeps (1 - F) exp(-sigma t) / n^2 of its radiance: a slab resting on the floor, seen from
// straight above, no lights. The same slab floating above the floor keeps (1 - F)^2 exp(-sigma t): its light
// leaves the water into air again before it meets the floor, and the two interfaces' n^2 cancel. So does a
// slab resting on the floor as a Mantaflow domain's liquid, whose box (where Mantaflow's mesh closes) stops
// short of the floor: air lies between the mesh and the floor.
TEST(GLLiquidLight, AFloorUnderWaterKeepsOneOverNSquaredOfItsRadiance) {
  TempDirectory directory;
  const double floorRadiance = 0.5;  // floorScene's colour
  enum class Slab { Resting, Floating, RestingInADomain };
  for (const Slab slab : {Slab::Resting, Slab::Floating, Slab::RestingInADomain}) {
    SCOPED_TRACE(slab == Slab::Resting    ? "slab resting on the floor"
                 : slab == Slab::Floating ? "slab floating above the floor"
                                          : "slab resting on the floor in a Mantaflow domain");
    Scene scene = floorScene(directory);
    scene.background.color =
        glm::vec3(0.0f);  // what the surface reflects: nothing, so only the floor is seen
    scene.parameters.liquid.absorption_rgb = {0.9f, 0.3f, 0.15f};
    if (slab == Slab::RestingInADomain) {
      ParticleSource source;
      source.role = ParticleRole::Liquid;
      source.domainBox = DomainBox{glm::mat4(1.0f), {-3.0f, -3.0f, 0.02f}, {3.0f, 3.0f, 3.0f}};
      scene.particles.push_back(source);
    }
    // Particles of radius 0.05 on a 0.05 lattice: the resting slab's drawn bottom touches the floor (z = 0),
    // the floating one's lies 0.45 (9 radii) above it.
    const float bottom = slab == Slab::Floating ? 0.5f : 0.05f;
    const RenderResult result = renderer().renderParticles(
        scene, slabParticles({-1.0f, -1.0f, bottom}, {1.0f, 1.0f, bottom + 0.4f}), 1);
    expectAllChannelsFinite(result);
    const double ior = scene.parameters.liquid.ior;
    int compared = 0;
    for (int row = kHeight / 2 - 6; row < kHeight / 2 + 6; ++row)
      for (int column = kWidth / 2 - 6; column < kWidth / 2 + 6; ++column) {
        // Within 2 degrees of straight down: Fresnel at normal incidence.
        const double fresnel = optics::schlick(1.0, ior);
        const double path = at(*result.layer("thickness"), kWidth, column, row, 0);
        ASSERT_GT(path, 0.3) << "no water at the image's centre";
        for (int c = 0; c < 3; ++c) {
          const double beer = std::exp(-scene.parameters.liquid.absorption_rgb[c] * path);
          const double expected = slab == Slab::Resting ? (1.0 - fresnel) * beer / (ior * ior)
                                                        : (1.0 - fresnel) * (1.0 - fresnel) * beer;
          EXPECT_NEAR(at(*result.layer("liquid"), kWidth, column, row, c), expected * floorRadiance,
                      0.02 * expected * floorRadiance);
          EXPECT_NEAR(at(*result.layer("transmittance"), kWidth, column, row, c), expected, 0.02 * expected);
        }
        ++compared;
      }
    EXPECT_EQ(compared, 144);
  }
}

// One sun whose caustics are on, beside the sky occlusion: the lit background finds its shadow itself and the
// shadow pass does not run (docs/frame-cost.md, session 44). The same sun with a second one of no strength
// goes through the shadow pass's sums, which the second adds nothing to: every light layer and the composite
// agree to rounding.
TEST(GLLiquidLight, TheLitBackgroundFindsOneSunsShadowAsTheShadowPassDoes) {
  TempDirectory directory;
  Scene scene = floorScene(directory);
  scene.lights.push_back(sunAlong({0.5f, 0.2f, -1.0f}));
  const Particles slab = slabParticles({-1.0f, -1.0f, 0.05f}, {0.5f, 1.0f, 0.5f});
  const RenderResult inPlace = renderer().renderParticles(scene, slab, 1);
  Scene twoSuns = scene;
  twoSuns.lights.push_back(sunAlong({-0.3f, 0.1f, -1.0f}, 0.0f));
  const RenderResult summed = renderer().renderParticles(twoSuns, slab, 1);
  expectAllChannelsFinite(inPlace);
  expectAllChannelsFinite(summed);
  const auto ran = [](const RenderResult& result, const std::string& pass) {
    for (const PassTiming& timing : result.stats.passes)
      if (timing.name == pass) return true;
    return false;
  };
  EXPECT_FALSE(ran(inPlace, "liquid_shadow"));
  EXPECT_TRUE(ran(summed, "liquid_shadow"));
  double shadowed = 0.0;
  for (const char* layer : {"composite", "liquid_shadow", "caustics", "liquid_sky"})
    for (int row = 0; row < kHeight; ++row)
      for (int column = 0; column < kWidth; ++column)
        for (int c = 0; c < 3; ++c) {
          const float a = at(*inPlace.layer(layer), kWidth, column, row, c);
          ASSERT_NEAR(a, at(*summed.layer(layer), kWidth, column, row, c), 1e-5)
              << layer << " at " << column << ", " << row << ", channel " << c;
          if (std::string(layer) == "liquid_shadow") shadowed += 1.0 - a;
        }
  EXPECT_GT(shadowed, 100.0) << "the slab shadows the floor";
}
