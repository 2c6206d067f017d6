// The ellipsoid impostors' screen rectangles (ellipsoid_impostor.vert, tight bounds after Sigg et al. 2006)
// never cut off a pixel of an ellipsoid: the front and back depth layers the GPU draws from the preparation's
// own ellipsoids are compared, pixel by pixel, with a double-precision CPU ray cast of every ellipsoid
// against every pixel (drawing all of them everywhere). Anisotropic, flattened ellipsoids at a grazing view
// are the case the rectangles shrink most.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "EllipsoidRayCast.h"
#include "LiquidTestScenes.h"
#include "prep/LiquidPreparation.h"
#include "prep/SurfaceRelaxation.h"
#include "prep/WindowRectangle.h"
#include "spindrift/Renderer.h"

using namespace spindrift;

namespace {

struct CpuLayers {
  std::vector<double> front, back;  // planar eye depth; 1e10 where empty
  std::vector<bool> ambiguous;      // a ray that grazes a silhouette, where float and double may differ
};

// Casts each pixel centre's ray against every ellipsoid: nearest entry (front) and farthest exit (back).
CpuLayers rayCast(const std::vector<EllipsoidInstance>& ellipsoids, const Camera& camera) {
  const int width = camera.width, height = camera.height;
  CpuLayers layers{std::vector<double>(std::size_t(width) * height, 1e10),
                   std::vector<double>(std::size_t(width) * height, 1e10),
                   std::vector<bool>(std::size_t(width) * height, false)};
  const glm::dvec3 origin = glm::dvec3(camera.position());
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column) {
      // A direction whose planar eye depth grows by one per unit of t.
      const glm::dvec3 direction =
          glm::dvec3(camera.worldFromPixelAndDepth({column + 0.5f, row + 0.5f}, 1.0f)) - origin;
      const std::size_t index = std::size_t(row) * width + column;
      double nearest = 1e10, farthest = -1.0;
      for (const EllipsoidInstance& ellipsoid : ellipsoids) {
        const ellipsoid_test::Chord chord = ellipsoid_test::castRay(ellipsoid, origin, direction);
        if (std::abs(chord.miss) < 2e-3) layers.ambiguous[index] = true;
        if (chord.miss < 0.0) continue;
        nearest = std::min(nearest, chord.entry);
        farthest = std::max(farthest, chord.exit);
      }
      if (nearest < 1e10) {
        layers.front[index] = nearest;
        layers.back[index] = farthest;
      }
    }
  return layers;
}

// A wavy sheet of liquid four particles thick with jitter: its surface particles become flattened ellipsoids.
Particles wavySheet() {
  return liquid_test::wavySheet(4, 7);
}

// The sheet seen at a grazing angle, where the rectangles shrink most.
Scene grazingView() {
  Scene scene;
  scene.camera =
      Camera::lookAt(160, 120, 40.0f, {0.0f, -1.3f, 0.35f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
  scene.camera.nearClip = 0.05f;
  scene.camera.farClip = 20.0f;
  return scene;
}

// The particles as the renderer draws them: relaxed onto their smooth surface (liquid.relax_surface), which
// raises some of the sheet's surface particles.
Particles drawnParticles(const Particles& particles, const LiquidParameters& parameters) {
  if (!relaxesSurface(parameters)) return particles;
  SurfaceRelaxationStats stats;
  return relaxLiquidSurface(particles, parameters, stats);
}

// A frame with the depth layers before smoothing kept (aggregate_front_depth, aggregate_front_normal, ...).
RenderResult renderIntermediateLayers(const Scene& scene, const Particles& particles) {
  Renderer renderer;
  renderer.setIntermediateLayers(true);
  renderer.setLayers({"depth"});
  return renderer.renderParticles(scene, particles, 1);
}

}  // namespace

TEST(GLImpostorBounds, TightRectanglesLoseNoPixelOfAnyEllipsoid) {
  const Scene scene = grazingView();
  const Particles particles = wavySheet();
  const LiquidPreparation preparation = prepareLiquid(drawnParticles(particles, scene.parameters.liquid),
                                                      scene.camera, scene.parameters.liquid);
  ASSERT_GT(preparation.aggregates.size(), 1000u);

  const RenderResult result = renderIntermediateLayers(scene, particles);
  const ImageLayer* front = result.layer("aggregate_front_depth");
  const ImageLayer* back = result.layer("aggregate_back_depth");
  ASSERT_NE(front, nullptr);
  ASSERT_NE(back, nullptr);
  const CpuLayers reference = rayCast(preparation.aggregates, scene.camera);

  std::size_t covered = 0, lost = 0, extra = 0, frontMismatch = 0, backMismatch = 0, compared = 0;
  for (std::size_t i = 0; i < reference.front.size(); ++i) {
    ASSERT_TRUE(std::isfinite(front->pixels[i]) && std::isfinite(back->pixels[i]));
    if (reference.ambiguous[i]) continue;
    const bool cpuCovered = reference.front[i] < 1e9, gpuCovered = front->pixels[i] < 1e9f;
    covered += cpuCovered;
    lost += cpuCovered && !gpuCovered;
    extra += !cpuCovered && gpuCovered;
    if (cpuCovered && gpuCovered) {
      ++compared;
      frontMismatch += std::abs(front->pixels[i] - reference.front[i]) > 1e-4 * reference.front[i];
      backMismatch += std::abs(back->pixels[i] - reference.back[i]) > 1e-4 * reference.back[i];
    }
  }
  RecordProperty("covered_pixels", int(covered));
  EXPECT_GT(covered, 2000u) << "the sheet fills much of the view";
  EXPECT_EQ(lost, 0u) << "pixels an ellipsoid covers that the impostors did not draw";
  EXPECT_EQ(extra, 0u);
  // Two ellipsoids whose surfaces cross within float precision may swap; nothing else may differ.
  EXPECT_LE(frontMismatch, compared / 500) << frontMismatch << " of " << compared;
  EXPECT_LE(backMismatch, compared / 500) << backMismatch << " of " << compared;
}

// The normal resolve (ellipsoid_normals.frag) repeats the ray cast of each pixel's winning ellipsoid only:
// every pixel's normal must be the analytic outward normal, M^T M (x - c) normalised, of the ellipsoid that a
// double-precision CPU ray cast finds nearest (front layer) or farthest (back layer) there.
TEST(GLImpostorBounds, EachPixelHasTheNormalOfTheEllipsoidThatHoldsIt) {
  const Scene scene = grazingView();
  const Particles particles = wavySheet();
  const std::vector<EllipsoidInstance> ellipsoids =
      prepareLiquid(drawnParticles(particles, scene.parameters.liquid), scene.camera, scene.parameters.liquid)
          .aggregates;

  const RenderResult result = renderIntermediateLayers(scene, particles);
  const ImageLayer* layers[2] = {result.layer("aggregate_front_normal"),
                                 result.layer("aggregate_back_normal")};
  ASSERT_NE(layers[0], nullptr);
  ASSERT_NE(layers[1], nullptr);

  const int width = scene.camera.width, height = scene.camera.height;
  const glm::dvec3 origin = glm::dvec3(scene.camera.position());
  std::size_t compared = 0, wrong = 0, missing = 0;
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column) {
      const glm::dvec3 direction =
          glm::dvec3(scene.camera.worldFromPixelAndDepth({column + 0.5f, row + 0.5f}, 1.0f)) - origin;
      // The winners of both layers, and how close the runners-up came (a near tie may go either way in
      // float).
      double best[2] = {1e10, -1e10}, runnerUp[2] = {1e10, -1e10};
      const EllipsoidInstance* winner[2] = {nullptr, nullptr};
      bool grazing = false;
      for (const EllipsoidInstance& ellipsoid : ellipsoids) {
        const ellipsoid_test::Chord chord = ellipsoid_test::castRay(ellipsoid, origin, direction);
        grazing = grazing || std::abs(chord.miss) < 2e-3;
        if (chord.miss < 0.0) continue;
        if (chord.entry < best[0]) {
          runnerUp[0] = best[0];
          best[0] = chord.entry;
          winner[0] = &ellipsoid;
        } else {
          runnerUp[0] = std::min(runnerUp[0], chord.entry);
        }
        if (chord.exit > best[1]) {
          runnerUp[1] = best[1];
          best[1] = chord.exit;
          winner[1] = &ellipsoid;
        } else {
          runnerUp[1] = std::max(runnerUp[1], chord.exit);
        }
      }
      const std::size_t pixel = std::size_t(row) * width + column;
      for (int layer = 0; layer < 2; ++layer) {
        const float* stored = &layers[layer]->pixels[3 * pixel];
        for (int c = 0; c < 3; ++c)
          ASSERT_TRUE(std::isfinite(stored[c]));
        if (!winner[layer] || grazing ||
            std::abs(runnerUp[layer] - best[layer]) < 1e-4 * std::abs(best[layer]))
          continue;
        const EllipsoidInstance& ellipsoid = *winner[layer];
        const glm::dmat3 inverseAxes = glm::transpose(glm::dmat3(glm::dvec3(ellipsoid.inverseAxesRows[0]),
                                                                 glm::dvec3(ellipsoid.inverseAxesRows[1]),
                                                                 glm::dvec3(ellipsoid.inverseAxesRows[2])));
        const glm::dvec3 point = origin + best[layer] * direction;
        const glm::dvec3 expected = glm::normalize(glm::transpose(inverseAxes) * inverseAxes *
                                                   (point - glm::dvec3(ellipsoid.centreAndBoundingRadius)));
        const glm::dvec3 drawn(stored[0], stored[1], stored[2]);
        ++compared;
        if (glm::length(drawn) < 0.5) {
          ++missing;
          continue;
        }
        // Half-float storage keeps a normal to about 0.1 degrees.
        wrong += glm::dot(glm::normalize(drawn), expected) < std::cos(glm::radians(1.0));
      }
    }
  RecordProperty("compared_pixels", int(compared));
  EXPECT_GT(compared, 4000u) << "both layers of the sheet fill much of the view";
  EXPECT_EQ(missing, 0u) << "pixels with a surface but no normal";
  EXPECT_LE(wrong, compared / 500) << wrong << " of " << compared << " normals off by more than 1 degree";
}

// The normal resolve shades only the rectangle that holds the drawn ellipsoids (prep/WindowRectangle.h) and
// clears the rest: a renderer that drew a sheet filling the view and then a small block in one corner gives
// the block's frame exactly the normals a fresh renderer gives it, so nothing of the sheet's is left
// outside the block's rectangle.
TEST(GLImpostorBounds, NormalsOutsideTheResolvedRectangleAreClearedBetweenFrames) {
  const Scene scene = grazingView();
  const Particles block =
      liquid_test::particlesOf(liquid_test::block({0.6f, 0.1f, 0.0f}, {0.9f, 0.3f, 0.15f}, 0.05f), 0.04f);
  const std::vector<EllipsoidInstance> blockEllipsoids =
      prepareLiquid(drawnParticles(block, scene.parameters.liquid), scene.camera, scene.parameters.liquid)
          .aggregates;
  const WindowRectangle rectangle = windowRectangleOfSpheres(blockEllipsoids, scene.camera);
  ASSERT_GT(rectangle.pixels(), 0);
  ASSERT_LT(rectangle.pixels(), (long long)scene.camera.width * scene.camera.height / 4)
      << "the block's rectangle must leave most of the view out for this test to say anything";

  Renderer reused;
  reused.setIntermediateLayers(true);
  reused.setLayers({"depth"});
  const RenderResult sheet = reused.renderParticles(scene, wavySheet(), 1);
  const RenderResult afterSheet = reused.renderParticles(scene, block, 2);
  const RenderResult fresh = renderIntermediateLayers(scene, block);
  std::size_t sheetNormals = 0;
  for (const char* name : {"aggregate_front_normal", "aggregate_back_normal"}) {
    const ImageLayer* drawnSheet = sheet.layer(name);
    const ImageLayer* reusedLayer = afterSheet.layer(name);
    const ImageLayer* freshLayer = fresh.layer(name);
    ASSERT_NE(drawnSheet, nullptr);
    ASSERT_NE(reusedLayer, nullptr);
    ASSERT_NE(freshLayer, nullptr);
    for (std::size_t i = 0; i < drawnSheet->pixels.size(); ++i)
      sheetNormals += drawnSheet->pixels[i] != 0.0f;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < freshLayer->pixels.size(); ++i)
      differing += reusedLayer->pixels[i] != freshLayer->pixels[i];
    EXPECT_EQ(differing, 0u) << name;
  }
  EXPECT_GT(sheetNormals, 10000u) << "the sheet left normals all over the view";
}
