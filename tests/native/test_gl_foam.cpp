// GL tests of the foam pipeline (foam paper, Akinci et al. 2013) on scenes built in code: the thickness and
// intensity of a known slab, hiding by solids, fading below a liquid surface, SSAO darkening in a bowl, the
// environment's hue, skipped passes and a million particles. Every render is checked for NaN and Inf.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <random>

#include <glm/trigonometric.hpp>

#include "BackgroundFiles.h"
#include "LiquidTestScenes.h"
#include "TempDirectory.h"
#include "prep/FoamPreparation.h"

using namespace spindrift;
using liquid_test::at;
using liquid_test::renderer;

namespace {

const char* kFoamLayers[] = {"foam",        "foam_spray",      "foam_surface",  "foam_bubble",
                             "foam_shadow", "foam_irradiance", "foam_thickness"};

void expectFiniteFoam(const RenderResult& result) {
  liquid_test::expectAllChannelsFinite(result);
  for (const char* layer : kFoamLayers)
    EXPECT_NE(result.layer(layer), nullptr) << layer;
}

// Every foam layer and the composite of two renders bit for bit the same.
void expectFoamLayersIdentical(const RenderResult& culled, const RenderResult& drawn) {
  for (const char* layer : {"composite", "foam", "foam_spray", "foam_surface", "foam_bubble", "foam_shadow",
                            "foam_irradiance", "foam_thickness"}) {
    const std::vector<float>& a = culled.layer(layer)->pixels;
    const std::vector<float>& b = drawn.layer(layer)->pixels;
    ASSERT_EQ(a.size(), b.size()) << layer;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
      differing += a[i] != b[i];
    EXPECT_EQ(differing, 0u) << layer;
  }
}

// A camera on +Z looking at the origin; odd sizes put the centre pixel's ray exactly on the view axis.
Scene sceneLookingDown(int size, float height = 5.0f) {
  Scene scene;
  scene.camera = Camera::lookAt(size, size, 30.0f, {0, 0, height}, {0, 0, 0}, {0, 1, 0});
  return scene;
}

void appendFoam(Particles& particles, const std::vector<glm::vec3>& positions, float radius,
                ParticleKind kind) {
  for (const glm::vec3& position : positions)
    particles.append(position, radius, kind, 0.0f, glm::vec3(0.0f));
}

double foamFalloff(double x, double b, double n, double m) {
  return x / b > 1.0 ? 0.0 : std::pow(1.0 - std::pow(x / b, n), m);
}

float centre(const RenderResult& result, const char* layer, int channel) {
  return at(*result.layer(layer), result.width, result.width / 2, result.height / 2, channel);
}

// Mean of a layer's channel over the pixels whose camera-space point on the plane z = 0 (for the camera of
// sceneLookingDown) lies at a distance from the axis within [inner, outer), where the foam is.
double meanOverRing(const RenderResult& result, const Scene& scene, const char* layer, int channel,
                    float inner, float outer, float planeDepth) {
  const float tanHalf = std::tan(glm::radians(scene.camera.fovYDegrees) * 0.5f);
  double sum = 0.0;
  int count = 0;
  for (int row = 0; row < result.height; ++row)
    for (int column = 0; column < result.width; ++column) {
      const float x = ((column + 0.5f) / result.width * 2 - 1) * tanHalf * planeDepth;
      const float y = ((row + 0.5f) / result.height * 2 - 1) * tanHalf * planeDepth;
      const float distance = std::hypot(x, y);
      if (distance < inner || distance >= outer) continue;
      if (at(*result.layer("foam"), result.width, column, row, 3) <= 0.0f) continue;
      sum += at(*result.layer(layer), result.width, column, row, channel);
      ++count;
    }
  EXPECT_GT(count, 20) << layer;
  return count ? sum / count : 0.0;
}

}  // namespace

TEST(GLFoam, SlabOfKnownThicknessGivesExpectedIntensity) {
  Scene scene = sceneLookingDown(65);
  Particles particles;
  appendFoam(particles, liquid_test::block({-0.3f, -0.3f, -0.15f}, {0.3f, 0.3f, 0.0f}, 0.05f), 0.04f,
             ParticleKind::Foam);
  const RenderResult result = renderer().renderParticles(scene, particles, 1);
  expectFiniteFoam(result);
  // The centre pixel's ray runs along the axis: each sprite contributes f(|centre.xy| / r, 1, 2.25, 1).
  const FoamParameters& parameters = scene.parameters.foam;
  const FoamPreparation foam = prepareFoam(particles, scene.camera, parameters);
  double expectedThickness = 0.0;
  for (const FoamInstance& instance : foam.instances) {
    const double offset = std::hypot(instance.centreAndRadius.x, instance.centreAndRadius.y);
    expectedThickness += foamFalloff(offset / instance.centreAndRadius.w, 1.0, 2.25, 1.0);
  }
  const double expectedIntensity =
      std::pow(expectedThickness, 1.25) / (3.0 + std::pow(expectedThickness, 1.25));
  EXPECT_GT(expectedThickness, 3.0);
  EXPECT_NEAR(centre(result, "foam_thickness", 0), expectedThickness, 1e-4 * expectedThickness);
  EXPECT_NEAR(centre(result, "foam", 3), expectedIntensity, 1e-5);
  EXPECT_NEAR(centre(result, "foam_surface", 3), expectedIntensity, 1e-5);  // all of it is surface foam
  EXPECT_EQ(centre(result, "foam_spray", 3), 0.0f);
  std::printf("[ measured ] slab: thickness %.5f (expected %.5f), intensity %.5f (expected %.5f)\n",
              centre(result, "foam_thickness", 0), expectedThickness, centre(result, "foam", 3),
              expectedIntensity);
}

TEST(GLFoam, FoamBehindSolidIsInvisible) {
  TempDirectory directory;
  const int size = 65;
  // A wall at eye depth 3 over the left half of the frame; nothing over the right half.
  writeBackgroundExr(
      directory.path() / "background.exr", size, size, [](int, int) { return glm::vec3(0.2f); },
      [&](int column, int) { return column < size / 2 ? 3.0f : 1e10f; });
  Scene scene = sceneLookingDown(size);
  scene.background.image = directory.path() / "background.exr";
  Particles particles;
  appendFoam(particles, liquid_test::block({-0.6f, -0.3f, 0.0f}, {0.6f, 0.3f, 0.0f}, 0.03f), 0.05f,
             ParticleKind::Foam);
  const RenderResult result = renderer().renderParticles(scene, particles, 1);
  expectFiniteFoam(result);
  const ImageLayer& foam = *result.layer("foam");
  const ImageLayer& composite = *result.layer("composite");
  double hiddenAlpha = 0.0, visibleAlpha = 0.0, largestChange = 0.0;
  for (int row = 20; row < 45; ++row)
    for (int column = 0; column < size; ++column) {
      if (column < size / 2) {
        hiddenAlpha = std::max<double>(hiddenAlpha, at(foam, size, column, row, 3));
        for (int channel = 0; channel < 3; ++channel)
          largestChange =
              std::max<double>(largestChange, std::abs(at(composite, size, column, row, channel) - 0.2f));
      } else if (column > size / 2 + 2) {
        visibleAlpha = std::max<double>(visibleAlpha, at(foam, size, column, row, 3));
      }
    }
  EXPECT_EQ(hiddenAlpha, 0.0);
  EXPECT_LT(largestChange, 1e-6);  // the composite there is the background, untouched
  EXPECT_GT(visibleAlpha, 0.5);
}

TEST(GLFoam, FoamBelowLiquidSurfaceFadesWithDepth) {
  TempDirectory directory;
  const int size = 33;
  // A render that includes a liquid surface at eye depth 4 everywhere (world z = 1), over no solids.
  writeBackgroundExr(
      directory.path() / "with_liquid.exr", size, size, [](int, int) { return glm::vec3(0.1f); },
      [](int, int) { return 4.0f; });
  Scene scene = sceneLookingDown(size);
  scene.background.image = directory.path() / "with_liquid.exr";
  scene.background.depth = directory.path() / "with_liquid.exr";
  scene.background.liquidDepth = directory.path() / "with_liquid.exr";
  scene.background.depthExplicit = true;
  // The solids lie farther than the liquid: a second file whose depth is 1e10.
  writeBackgroundExr(
      directory.path() / "solids.exr", size, size, [](int, int) { return glm::vec3(0.1f); },
      [](int, int) { return 1e10f; });
  scene.background.depth = directory.path() / "solids.exr";
  const FoamParameters& parameters = scene.parameters.foam;
  const float radius = 0.05f;
  double previous = 2.0;
  for (const float below : {-0.1f, 0.0f, 0.05f, 0.1f, 0.15f, 0.2f, 0.25f, 0.29f, 0.35f}) {
    // One surface-foam particle on the axis whose sphere's front lies `below` under the surface.
    Particles particles;
    appendFoam(particles, {{0.0f, 0.0f, 1.0f - below - radius}}, radius, ParticleKind::Foam);
    const RenderResult result = renderer().renderParticles(scene, particles, 1);
    expectFiniteFoam(result);
    const double expected = below <= 0.0f ? 1.0
                                          : foamFalloff(below, parameters.attenuation_distance,
                                                        parameters.attenuation_n, parameters.attenuation_m);
    const float thickness = centre(result, "foam_thickness", 0);
    EXPECT_NEAR(thickness, expected, 2e-4) << below << " below the surface";
    EXPECT_LE(thickness, previous + 1e-6);
    previous = thickness;
    std::printf("[ measured ] %.2f below the surface: thickness %.5f, f_att %.5f\n", below, thickness,
                expected);
  }
}

// foam.cull_hidden: spray behind a wall and bubbles deeper under the liquid than attenuation_distance are not
// drawn, and every foam layer and the composite stay exactly what drawing every particle gives.
TEST(GLFoam, HiddenFoamIsLeftOutAndChangesNoLayer) {
  TempDirectory directory;
  const int size = 65;
  // A render with a liquid surface at eye depth 4 (world z = 1) everywhere; the solids: a wall at eye depth 3
  // over the left third of the frame, nothing elsewhere.
  writeBackgroundExr(
      directory.path() / "with_liquid.exr", size, size, [](int, int) { return glm::vec3(0.1f, 0.2f, 0.3f); },
      [](int, int) { return 4.0f; });
  writeBackgroundExr(
      directory.path() / "solids.exr", size, size, [](int, int) { return glm::vec3(0.1f, 0.2f, 0.3f); },
      [&](int column, int) { return column < size / 3 ? 3.0f : 1e10f; });
  Scene scene = sceneLookingDown(size);
  scene.background.image = directory.path() / "with_liquid.exr";
  scene.background.depth = directory.path() / "solids.exr";
  scene.background.liquidDepth = directory.path() / "with_liquid.exr";
  scene.background.depthExplicit = true;
  const float radius = 0.04f;
  const std::vector<glm::vec3> behindWall =
      liquid_test::block({-0.85f, -0.4f, 1.5f}, {-0.65f, 0.4f, 1.5f}, 0.04f);
  const std::vector<glm::vec3> deepBubbles =
      liquid_test::block({0.0f, -0.5f, 0.4f}, {0.5f, -0.2f, 0.5f}, 0.05f);
  Particles particles;
  appendFoam(particles, behindWall, radius, ParticleKind::Spray);
  appendFoam(particles, deepBubbles, radius, ParticleKind::Bubble);
  // What stays: surface foam on the liquid, bubbles just under it, spray in front of the wall.
  appendFoam(particles, liquid_test::block({-0.1f, -0.1f, 0.98f}, {0.6f, 0.5f, 0.98f}, 0.04f), radius,
             ParticleKind::Foam);
  appendFoam(particles, liquid_test::block({0.0f, -0.15f, 0.8f}, {0.5f, 0.5f, 0.85f}, 0.05f), radius,
             ParticleKind::Bubble);
  appendFoam(particles, liquid_test::block({-0.7f, -0.3f, 2.3f}, {-0.5f, 0.3f, 2.3f}, 0.05f), radius,
             ParticleKind::Spray);
  // The hidden foam's test alone: sub-pixel sprites would be left out before it, and not counted by it.
  scene.parameters.foam.cull_sub_pixel = false;
  const RenderResult culled = renderer().renderParticles(scene, particles, 1);
  scene.parameters.foam.cull_hidden = false;
  const RenderResult drawn = renderer().renderParticles(scene, particles, 1);
  expectFiniteFoam(culled);
  EXPECT_EQ(culled.stats.foam.hiddenBehindSolids, behindWall.size());
  EXPECT_EQ(culled.stats.foam.hiddenUnderLiquid, deepBubbles.size());
  EXPECT_EQ(drawn.stats.foam.hiddenBehindSolids + drawn.stats.foam.hiddenUnderLiquid, 0u);
  bool skippedWithReason = false;
  for (const SkippedPass& pass : drawn.stats.skipped)
    skippedWithReason |= pass.name == "foam_visibility" && pass.reason == "foam.cull_hidden is off";
  EXPECT_TRUE(skippedWithReason);
  double visible = 0.0;
  expectFoamLayersIdentical(culled, drawn);
  for (float alpha : culled.layer("foam_bubble")->pixels)
    visible = std::max<double>(visible, alpha);
  EXPECT_GT(visible, 0.02);  // the shallow bubbles show: the test looks at foam that is drawn
}

// foam.cull_sub_pixel: foam of every size from a tenth of a pixel to a few pixels, spread at random over the
// view at several depths (over and under a liquid surface, so the attenuation and the bubbles count too).
// The sprites that hold no pixel's centre are not drawn, and every foam layer and the composite stay exactly
// what drawing every particle gives.
TEST(GLFoam, SubPixelFoamIsLeftOutAndChangesNoLayer) {
  TempDirectory directory;
  const int size = 65;
  writeBackgroundExr(
      directory.path() / "with_liquid.exr", size, size, [](int, int) { return glm::vec3(0.1f, 0.2f, 0.3f); },
      [](int, int) { return 4.5f; });
  Scene scene = sceneLookingDown(size);  // a pixel is 0.0412 units wide at eye depth 5 (z = 0)
  scene.background.image = directory.path() / "with_liquid.exr";
  scene.background.liquidDepth = directory.path() / "with_liquid.exr";
  std::mt19937 random(11);
  std::uniform_real_distribution<float> across(-1.0f, 1.0f), height(-0.3f, 1.5f), radius(0.004f, 0.08f);
  Particles particles;
  const ParticleKind kinds[] = {ParticleKind::Spray, ParticleKind::Foam, ParticleKind::Bubble};
  for (int i = 0; i < 3000; ++i)
    particles.append({across(random), across(random), height(random)}, radius(random), kinds[i % 3], 0.0f,
                     glm::vec3(0.0f));
  const RenderResult culled = renderer().renderParticles(scene, particles, 1);
  scene.parameters.foam.cull_sub_pixel = false;
  const RenderResult drawn = renderer().renderParticles(scene, particles, 1);
  expectFiniteFoam(culled);
  const FoamFrameStats& counts = culled.stats.foam;
  EXPECT_GT(counts.subPixel, 300u);
  EXPECT_LT(counts.subPixel, 2700u);
  EXPECT_EQ(drawn.stats.foam.subPixel, 0u);
  EXPECT_EQ(
      counts.sprayParticles + counts.surfaceParticles + counts.bubbleParticles,
      drawn.stats.foam.sprayParticles + drawn.stats.foam.surfaceParticles + drawn.stats.foam.bubbleParticles);
  expectFoamLayersIdentical(culled, drawn);
  double thickness = 0.0;
  for (float value : culled.layer("foam_thickness")->pixels)
    thickness = std::max<double>(thickness, value);
  EXPECT_GT(thickness, 0.0);  // foam is drawn: the comparison is not of two empty frames
  std::printf("[ measured ] %zu of 3000 sprites hold no pixel centre\n", counts.subPixel);
}

// Surface foam in a hemispherical bowl of radius 0.3 (rim at z = 0, bottom at z = -0.3) in a flat field out
// to 0.7.
Particles bowlOfFoam() {
  Particles particles;
  const float bowlRadius = 0.3f;
  for (const glm::vec3& point : liquid_test::block({-0.7f, -0.7f, 0.0f}, {0.7f, 0.7f, 0.0f}, 0.015f)) {
    const float distance = std::hypot(point.x, point.y);
    if (distance > 0.7f) continue;
    const float z = distance < bowlRadius ? -std::sqrt(bowlRadius * bowlRadius - distance * distance) : 0.0f;
    particles.append({point.x, point.y, z}, 0.03f, ParticleKind::Foam, 0.0f, glm::vec3(0.0f));
  }
  return particles;
}

TEST(GLFoam, ConcaveBowlIsDarkerThanRim) {
  Scene scene = sceneLookingDown(161, 3.0f);
  scene.background.color = glm::vec3(1.0f);  // a white environment lights the foam: I_final = 1
  const Particles particles = bowlOfFoam();
  const RenderResult result = renderer().renderParticles(scene, particles, 1);
  expectFiniteFoam(result);
  const double bowlShadow = meanOverRing(result, scene, "foam_shadow", 0, 0.0f, 0.12f, 3.3f);
  const double rimShadow = meanOverRing(result, scene, "foam_shadow", 0, 0.45f, 0.65f, 3.0f);
  const double bowlColour = meanOverRing(result, scene, "foam", 0, 0.0f, 0.12f, 3.3f);
  const double rimColour = meanOverRing(result, scene, "foam", 0, 0.45f, 0.65f, 3.0f);
  std::printf(
      "[ measured ] bowl: shadow %.4f, foam red %.4f; rim: shadow %.4f, foam red %.4f; AO samples/pixel "
      "%.0f\n",
      bowlShadow, bowlColour, rimShadow, rimColour, result.stats.foam.aoSamplesPerPixel);
  EXPECT_GT(bowlShadow, 1.5 * rimShadow);
  EXPECT_GT(bowlShadow, rimShadow + 0.02);
  EXPECT_LT(bowlColour, rimColour);
}

// foam.occlusion_block estimates the shadow and irradiance once per block, at its nearest foam pixel, and
// spreads them by depth: the bowl with a sheet of spray 1.5 above it (its edges cross the bowl's foam, at a
// very different depth), on a 161-pixel frame that blocks of 2 and 4 do not divide, against every pixel's
// own estimate.
TEST(GLFoam, OcclusionEstimatedPerBlockFollowsEveryPixelsEstimate) {
  Scene scene = sceneLookingDown(161, 3.0f);
  scene.background.color = glm::vec3(1.0f);
  Particles particles = bowlOfFoam();
  appendFoam(particles, liquid_test::block({-0.2f, -0.05f, 1.5f}, {0.2f, 0.05f, 1.5f}, 0.01f), 0.015f,
             ParticleKind::Spray);
  scene.parameters.foam.occlusion_block = 1;
  const RenderResult everyPixel = renderer().renderParticles(scene, particles, 1);
  expectFiniteFoam(everyPixel);
  EXPECT_EQ(everyPixel.stats.foam.occlusionEstimates, everyPixel.stats.foam.foamPixels);
  const auto value = [](const RenderResult& result, const char* layer, int x, int y) {
    return at(*result.layer(layer), result.width, x, y, 0);
  };
  for (const int block : {2, 4}) {
    SCOPED_TRACE("block " + std::to_string(block));
    scene.parameters.foam.occlusion_block = block;
    const RenderResult blocks = renderer().renderParticles(scene, particles, 1);
    expectFiniteFoam(blocks);
    const FoamFrameStats& stats = blocks.stats.foam;
    EXPECT_EQ(stats.foamPixels, everyPixel.stats.foam.foamPixels);
    EXPECT_LT(stats.occlusionEstimates, stats.foamPixels / (block * block) + 2 * 161 / block);
    EXPECT_LT(stats.aoSamplesPerPixel, everyPixel.stats.foam.aoSamplesPerPixel / (0.5 * block * block));
    // Every foam pixel has an estimate: under the white sky its irradiance is lit, never left at 0.
    double sum = 0.0, signedSum = 0.0, largest = 0.0;
    int count = 0;
    for (int y = 0; y < 161; ++y)
      for (int x = 0; x < 161; ++x) {
        if (at(*everyPixel.layer("foam"), 161, x, y, 3) <= 0.0f) continue;
        EXPECT_GT(value(everyPixel, "foam_irradiance", x, y), 0.5f) << "pixel " << x << ", " << y;
        EXPECT_GT(value(blocks, "foam_irradiance", x, y), 0.5f) << "pixel " << x << ", " << y;
        const double difference = value(blocks, "foam_shadow", x, y) - value(everyPixel, "foam_shadow", x, y);
        sum += std::abs(difference);
        signedSum += difference;
        largest = std::max(largest, std::abs(difference));
        ++count;
      }
    std::printf(
        "[ measured ] block %d: %zu estimates for %zu foam pixels; shadow off by %.4f on average (%+.4f "
        "signed), %.4f at most\n",
        block, stats.occlusionEstimates, stats.foamPixels, sum / count, signedSum / count, largest);
    EXPECT_LT(sum / count, 0.01 * block);
    // Unbiased: estimating at each block's nearest foam pixel, the least occluded, lightened the shadow.
    EXPECT_LT(std::abs(signedSum / count), 0.001 * block);
    EXPECT_LT(largest, 0.1);
  }
}

TEST(GLFoam, RedEnvironmentTintsFoamFacingIt) {
  TempDirectory directory;
  // An equirectangular environment: red towards +X (u in (0.25, 0.75)), grey elsewhere.
  const int width = 64, height = 32;
  std::vector<float> pixels(std::size_t(width) * height * 3);
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column) {
      const float u = (column + 0.5f) / width;
      const bool red = u > 0.25f && u < 0.75f;
      float* pixel = &pixels[(std::size_t(row) * width + column) * 3];
      pixel[0] = red ? 1.0f : 0.5f;
      pixel[1] = red ? 0.0f : 0.5f;
      pixel[2] = red ? 0.0f : 0.5f;
    }
  const std::string environment = (directory.path() / "environment.exr").string();
  auto output = OIIO::ImageOutput::create(environment);
  output->open(environment, OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT));
  output->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
  output->close();

  for (const char* method : {"samples", "irradiance_map"}) {
    double redOverGreen[2];
    for (int side = 0; side < 2; ++side) {
      // The foam faces the camera: from +X it faces the red half, from -X the grey half.
      const float x = side == 0 ? 5.0f : -5.0f;
      Scene scene;
      scene.camera = Camera::lookAt(65, 65, 30.0f, {x, 0, 0}, {0, 0, 0}, {0, 0, 1});
      scene.background.environment = environment;
      scene.parameters.foam.irradiance = method;
      Particles particles;
      appendFoam(particles, liquid_test::block({0.0f, -0.3f, -0.3f}, {0.0f, 0.3f, 0.3f}, 0.03f), 0.05f,
                 ParticleKind::Foam);
      const RenderResult result = renderer().renderParticles(scene, particles, 1);
      expectFiniteFoam(result);
      const float red = centre(result, "foam_irradiance", 0), green = centre(result, "foam_irradiance", 1);
      redOverGreen[side] = red / std::max(green, 1e-6f);
      std::printf("[ measured ] %s, camera at x = %+.0f: irradiance (%.3f, %.3f, %.3f)\n", method, x, red,
                  green, centre(result, "foam_irradiance", 2));
    }
    EXPECT_GT(redOverGreen[0], 2.0) << method;
    EXPECT_LT(redOverGreen[1], 1.5) << method;
  }
}

// foam.lit_by_lights: each light adds E cos(theta) / (2 pi) to the irradiance I, E its irradiance facing it
// (a sun's strength, a point's or spot's power over 4 pi d^2), theta the angle between the foam's normal and
// the way to the light, so that I_final = C_IrrScale I (C_IrrScale 2) gains a white diffuse surface's
// radiance E cos(theta) / pi. One sphere of foam under the camera's axis: the centre pixel's fragment lies at
// (0, 0, 1) with normal +Z, estimated alone (occlusion_block 1) and left unblurred (blur_radius_factor 0), so
// the gain there is exact up to the irradiance's half floats.
TEST(GLFoam, LightsAddTheirDirectIrradianceToTheFoams) {
  const auto render = [](const std::vector<Light>& lights, bool litByLights = true) {
    Scene scene = sceneLookingDown(65);
    scene.background.color = glm::vec3(0.2f, 0.25f, 0.3f);
    scene.parameters.foam.occlusion_block = 1;
    scene.parameters.foam.blur_radius_factor = 0.0f;
    scene.parameters.foam.lit_by_lights = litByLights;
    scene.lights = lights;
    Particles particles;
    appendFoam(particles, {glm::vec3(0.0f)}, 1.0f, ParticleKind::Foam);
    const RenderResult result = renderer().renderParticles(scene, particles, 1);
    expectFiniteFoam(result);
    return result;
  };
  const auto sun = [](const glm::vec3& travel, float strength, const glm::vec3& color = glm::vec3(1.0f)) {
    Light light;
    light.direction = glm::normalize(travel);
    light.strength = strength;
    light.color = color;
    return light;
  };
  const RenderResult unlit = render({});
  EXPECT_EQ(unlit.stats.foam.lights, 0u);
  const auto gain = [&](const RenderResult& lit, int channel) {
    return centre(lit, "foam_irradiance", channel) - centre(unlit, "foam_irradiance", channel);
  };
  constexpr double kPi = 3.14159265358979;
  constexpr double kTolerance = 2e-3;  // RGBA16F
  struct Case {
    const char* name;
    std::vector<Light> lights;
    glm::dvec3 expected;  // E cos(theta) / pi per channel
  };
  Light point;
  point.type = Light::Type::Point;
  point.position = {0.0f, 0.0f, 3.0f};  // 2 above the fragment
  point.strength = 40.0f;
  Light spotAtIt = point, spotAway = point;
  spotAtIt.type = spotAway.type = Light::Type::Spot;
  spotAtIt.direction = {0.0f, 0.0f, -1.0f};
  spotAway.direction = {1.0f, 0.0f, 0.0f};
  const double pointGain = 40.0 / (4.0 * kPi * 4.0) / kPi;
  const double theta = glm::radians(60.0);
  std::vector<Case> cases = {
      {"sun straight down", {sun({0, 0, -1}, 1.5f)}, glm::dvec3(1.5 / kPi)},
      {"sun 60 degrees off the normal",
       {sun({float(std::sin(theta)), 0.0f, -float(std::cos(theta))}, 1.5f)},
       glm::dvec3(1.5 * 0.5 / kPi)},
      {"red sun", {sun({0, 0, -1}, 1.5f, {1.0f, 0.0f, 0.0f})}, {1.5 / kPi, 0.0, 0.0}},
      {"sun from below the foam", {sun({0, 0, 1}, 1.5f)}, glm::dvec3(0.0)},
      {"sun of no strength", {sun({0, 0, -1}, 0.0f)}, glm::dvec3(0.0)},
      {"point light 2 above", {point}, glm::dvec3(pointGain)},
      {"spot pointing at the foam", {spotAtIt}, glm::dvec3(pointGain)},
      {"spot pointing away", {spotAway}, glm::dvec3(0.0)},
      {"two suns add", {sun({0, 0, -1}, 0.5f), sun({0, 0, -1}, 1.0f)}, glm::dvec3(1.5 / kPi)},
  };
  for (const Case& c : cases) {
    const RenderResult lit = render(c.lights);
    EXPECT_EQ(lit.stats.foam.lights, c.lights.size()) << c.name;
    for (int channel = 0; channel < 3; ++channel)
      EXPECT_NEAR(gain(lit, channel), c.expected[channel], kTolerance) << c.name << ", channel " << channel;
    std::printf("[ measured ] %s: irradiance gain (%.4f, %.4f, %.4f), expected (%.4f, %.4f, %.4f)\n", c.name,
                gain(lit, 0), gain(lit, 1), gain(lit, 2), c.expected.x, c.expected.y, c.expected.z);
  }
  // A light that adds nothing changes no foam layer; foam.lit_by_lights false ignores the lights.
  expectFoamLayersIdentical(render({sun({0, 0, 1}, 1.5f)}), unlit);
  const RenderResult ignored = render({sun({0, 0, -1}, 1.5f)}, false);
  EXPECT_EQ(ignored.stats.foam.lights, 0u);
  expectFoamLayersIdentical(ignored, unlit);
}

TEST(GLFoam, NoFoamInViewSkipsFoamPasses) {
  Scene scene = sceneLookingDown(33);
  Particles particles;
  appendFoam(particles, {{0.0f, 0.0f, 10.0f}}, 0.05f, ParticleKind::Spray);  // behind the camera
  const RenderResult result = renderer().renderParticles(scene, particles, 1);
  expectFiniteFoam(result);
  int skippedFoamPasses = 0;
  for (const SkippedPass& pass : result.stats.skipped)
    skippedFoamPasses += pass.name.rfind("foam_", 0) == 0 && pass.reason == "no foam particles in view";
  EXPECT_EQ(skippedFoamPasses, 8);
  for (const PassTiming& pass : result.stats.passes)
    EXPECT_NE(pass.name.rfind("foam_", 0), 0u) << pass.name;
  EXPECT_EQ(result.stats.foam.culled, 1u);
  for (const char* layer : kFoamLayers)
    for (float value : result.layer(layer)->pixels)
      ASSERT_EQ(value, 0.0f) << layer;
}

TEST(GLFoam, OneMillionParticlesRender) {
  Scene scene = sceneLookingDown(321);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  std::uniform_int_distribution<int> kind(0, 2);
  const ParticleKind kinds[] = {ParticleKind::Spray, ParticleKind::Foam, ParticleKind::Bubble};
  Particles particles;
  particles.reserve(1000000);
  for (int i = 0; i < 1000000; ++i)
    particles.append({coordinate(random), coordinate(random), 0.5f * coordinate(random)}, 0.01f,
                     kinds[kind(random)], float(i % 25), glm::vec3(0.0f));
  scene.parameters.foam.lifetime_frames = 25.0f;
  const RenderResult result = renderer().renderParticles(scene, particles, 1);
  expectFiniteFoam(result);
  const FoamFrameStats& foam = result.stats.foam;
  EXPECT_EQ(foam.sprayParticles + foam.surfaceParticles + foam.bubbleParticles + foam.culled, 1000000u);
  EXPECT_GT(foam.foamPixels, 50000u);
  double gpu = 0.0;
  for (const PassTiming& pass : result.stats.passes)
    gpu += pass.gpuMilliseconds;
  std::printf(
      "[ measured ] 1M foam particles at 321x321: %zu foam pixels, %.0f AO samples/pixel, %.0f ms GPU\n",
      foam.foamPixels, foam.aoSamplesPerPixel, gpu);
}
