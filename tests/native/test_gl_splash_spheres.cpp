// GL tests: they run on whatever EGL gives (Mesa's llvmpipe in CI) and fail, not skip, without OpenGL. A lone
// particle is a splash, drawn as an exact sphere: its depth and normal layers must match the analytic sphere.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>

#include <OpenImageIO/imageio.h>

#include "SphereReference.h"
#include "TempDirectory.h"
#include "spindrift/Renderer.h"

using namespace spindrift;

namespace {

Scene sphereScene() {
  Scene scene;
  scene.camera = Camera::lookAt(160, 120, 40.0f, {0, -5, 0}, {0, 0, 0}, {0, 0, 1});
  scene.background.color = {0.1f, 0.2f, 0.3f};
  return scene;
}

Particles particlesAt(std::initializer_list<std::pair<glm::vec3, float>> spheres) {
  Particles particles;
  for (const auto& [centre, radius] : spheres)
    particles.append(centre, radius, ParticleKind::Liquid, 0.0f, glm::vec3(0));
  return particles;
}

float channel(const ImageLayer& layer, int width, int column, int row, int channelIndex) {
  return layer.pixels[(std::size_t(row) * width + column) * layer.channelCount() + channelIndex];
}

void expectAllFinite(const RenderResult& result) {
  for (const ImageLayer& layer : result.layers) {
    std::size_t bad = 0;
    for (float value : layer.pixels)
      bad += !std::isfinite(value);
    EXPECT_EQ(bad, 0u) << "non-finite values in layer " << layer.name;
  }
}

// One renderer for the suite: making contexts is the slow part on llvmpipe.
Renderer& sharedRenderer() {
  static Renderer renderer;
  return renderer;
}

}  // namespace

TEST(GLSplashSpheres, DepthAndNormalMatchTheAnalyticSphere) {
  const Scene scene = sphereScene();
  const glm::dvec3 centre(0.2, 0.0, 0.1);
  const double radius = 0.8;
  const RenderResult result =
      sharedRenderer().renderParticles(scene, particlesAt({{glm::vec3(centre), float(radius)}}), 1);
  ASSERT_NE(result.layer("depth"), nullptr);
  ASSERT_NE(result.layer("normal"), nullptr);
  const ImageLayer& depth = *result.layer("depth");
  const ImageLayer& normal = *result.layer("normal");
  const int width = scene.camera.width;

  double worstDepthError = 0.0, worstNormalError = 0.0;
  int compared = 0, coverageMismatches = 0;
  for (int row = 0; row < scene.camera.height; ++row)
    for (int column = 0; column < width; ++column) {
      const auto hit = raySphere(scene.camera, column, row, centre, radius);
      const float renderedDepth = channel(depth, width, column, row, 0);
      const bool covered = renderedDepth < 1e9f;
      // Pixel centres within a hair of the silhouette may fall either way in float arithmetic.
      if (hit && hit->discriminantOverRadiusSquared < 1e-4) continue;
      if (covered != bool(hit)) {
        ++coverageMismatches;
        continue;
      }
      if (!hit) continue;
      ++compared;
      worstDepthError = std::max(worstDepthError, std::abs(renderedDepth - hit->eyeDepth));
      const glm::dvec3 rendered(channel(normal, width, column, row, 0),
                                channel(normal, width, column, row, 1),
                                channel(normal, width, column, row, 2));
      worstNormalError = std::max(worstNormalError, glm::length(rendered - hit->worldNormal));
    }
  EXPECT_GT(compared, 2000) << "the sphere covers about pi * 26^2 pixels";
  EXPECT_EQ(coverageMismatches, 0);
  EXPECT_LT(worstDepthError, 1e-3 * radius);
  EXPECT_LT(worstNormalError, 2e-3) << "normals are stored at half precision";
  expectAllFinite(result);
}

TEST(GLSplashSpheres, NearestSphereWins) {
  const Scene scene = sphereScene();
  // A small sphere in front of a big one, and the same pair listed the other way round.
  for (bool smallFirst : {true, false}) {
    const Particles particles = smallFirst ? particlesAt({{{0, -2, 0}, 0.2f}, {{0, 0, 0}, 1.0f}})
                                           : particlesAt({{{0, 0, 0}, 1.0f}, {{0, -2, 0}, 0.2f}});
    const RenderResult result = sharedRenderer().renderParticles(scene, particles, 1);
    const ImageLayer& depth = *result.layer("depth");
    const int column = scene.camera.width / 2, row = scene.camera.height / 2;
    const auto expected = raySphere(scene.camera, column, row, {0, -2, 0}, 0.2);
    ASSERT_TRUE(expected);
    EXPECT_NEAR(channel(depth, scene.camera.width, column, row, 0), expected->eyeDepth, 1e-4);
  }
}

TEST(GLSplashSpheres, BackgroundDepthHidesSpheresBehindSolids) {
  TempDirectory directory;
  Scene scene = sphereScene();
  const int width = scene.camera.width, height = scene.camera.height;
  // A wall at eye depth 4.5 over the left half of the frame, nothing on the right. The sphere's front reaches
  // depth 4.2, so on the left only its cap nearer than 4.5 shows.
  const float wallDepth = 4.5f;
  std::vector<float> depthPixels(std::size_t(width) * height);
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column)
      depthPixels[std::size_t(row) * width + column] = column < width / 2 ? wallDepth : 1e10f;
  const std::filesystem::path depthFile = directory.path() / "depth.exr";
  {
    auto output = OIIO::ImageOutput::create(depthFile.string());
    OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"ViewLayer.Depth.Z"};
    ASSERT_TRUE(output->open(depthFile.string(), spec));
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, depthPixels.data()));
    output->close();
  }
  scene.background.depth = depthFile;
  scene.background.depthExplicit = true;
  const glm::dvec3 centre(0, 0, 0);
  const RenderResult result =
      sharedRenderer().renderParticles(scene, particlesAt({{glm::vec3(centre), 0.8f}}), 1);
  const ImageLayer& depth = *result.layer("depth");
  int mismatches = 0, visibleOnLeft = 0;
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column) {
      const auto hit = raySphere(scene.camera, column, row, centre, 0.8);
      if (hit && hit->discriminantOverRadiusSquared < 1e-4) continue;
      if (hit && std::abs(hit->eyeDepth - wallDepth) < 1e-4) continue;
      const bool expected = hit && (column >= width / 2 || hit->eyeDepth < wallDepth);
      const bool covered = channel(depth, width, column, row, 0) < 1e9f;
      mismatches += expected != covered;
      visibleOnLeft += covered && column < width / 2;
    }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(visibleOnLeft, 50) << "the cap in front of the wall must show";
}

TEST(GLSplashSpheres, CompositeIsLiquidOverBackground) {
  const Scene scene = sphereScene();
  const RenderResult result = sharedRenderer().renderParticles(scene, particlesAt({{{0, 0, 0}, 0.5f}}), 1);
  const ImageLayer& composite = *result.layer("composite");
  const ImageLayer& liquid = *result.layer("liquid");
  const int width = scene.camera.width;
  // A corner shows the background colour; the centre shows the liquid, opaque.
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(channel(composite, width, 0, 0, c), scene.background.color[c], 1e-6f);
  EXPECT_EQ(channel(liquid, width, 0, 0, 3), 0.0f);
  const int column = width / 2, row = scene.camera.height / 2;
  EXPECT_EQ(channel(liquid, width, column, row, 3), 1.0f);
  for (int c = 0; c < 4; ++c)
    EXPECT_EQ(channel(composite, width, column, row, c), channel(liquid, width, column, row, c));
  expectAllFinite(result);
}

TEST(GLSplashSpheres, EmptyFrameSkipsLiquidPassesAndKeepsLayers) {
  const Scene scene = sphereScene();
  // One sphere behind the camera: loaded, culled, nothing drawn.
  const RenderResult result = sharedRenderer().renderParticles(scene, particlesAt({{{0, -10, 0}, 0.5f}}), 1);
  EXPECT_EQ(result.stats.liquid.splashParticles + result.stats.liquid.aggregateParticles, 0u);
  EXPECT_EQ(result.stats.liquid.culled, 1u);
  bool splashLayersSkipped = false;
  for (const SkippedPass& pass : result.stats.skipped)
    splashLayersSkipped |= pass.name == "splash_depth_layers";
  EXPECT_TRUE(splashLayersSkipped);
  for (const char* name : {"composite", "liquid", "depth", "normal"})
    EXPECT_NE(result.layer(name), nullptr) << name;
  for (float value : result.layer("depth")->pixels)
    ASSERT_EQ(value, 1e10f);
  for (const PassTiming& pass : result.stats.passes)
    EXPECT_GE(pass.gpuMilliseconds, 0.0) << pass.name;
  expectAllFinite(result);
}

TEST(GLSplashSpheres, ReportsTheGlRenderer) {
  EXPECT_FALSE(sharedRenderer().glRenderer().empty());
  EXPECT_NE(sharedRenderer().glVersion().find("4."), std::string::npos) << sharedRenderer().glVersion();
}
