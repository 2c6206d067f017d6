// The ray-marched surface (liquid.surface = raymarch, docs/raymarch.md) on llvmpipe-sized scenes: the binary
// density grid against a brute-force CPU density, adaptive against uniform stepping, tile resolutions of flat
// and splashing water, a one-particle-thick sheet, a lone particle against the analytic sphere, and
// degenerate frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

#include "LiquidTestScenes.h"
#include "RaymarchGridCheck.h"

using namespace spindrift;
using liquid_test::at;
using liquid_test::block;
using liquid_test::particlesOf;

namespace {

constexpr float kRadius = 0.05f;  // particle radius r; the blocks' spacing is r, as in Mantaflow's caches
constexpr int kWidth = 96, kHeight = 72;

Scene raymarchScene(const glm::vec3& eye, const glm::vec3& target) {
  Scene scene;
  scene.camera = Camera::lookAt(kWidth, kHeight, 40.0f, eye, target, {0, 0, 1});
  scene.background.color = {0.2f, 0.3f, 0.4f};
  scene.parameters.liquid.surface = "raymarch";
  return scene;
}

std::vector<glm::vec3> randomPoints(std::size_t count, const glm::vec3& low, const glm::vec3& high,
                                    unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<glm::vec3> points;
  for (std::size_t i = 0; i < count; ++i)
    points.push_back(low + (high - low) * glm::vec3(unit(generator), unit(generator), unit(generator)));
  return points;
}

// A pool 1 x 1 x 0.15 and droplets above it, so that rays pass splashes on their way to the body.
std::vector<glm::vec3> poolWithDroplets() {
  std::vector<glm::vec3> positions = block({-0.5f, -0.5f, -0.15f}, {0.5f, 0.5f, 0.0f}, kRadius);
  for (const glm::vec3& p : randomPoints(60, {-0.4f, -0.4f, 0.15f}, {0.4f, 0.4f, 0.6f}, 7))
    positions.push_back(p);
  return positions;
}

RenderResult render(const Scene& scene, const std::vector<glm::vec3>& positions) {
  return liquid_test::renderer().renderParticles(scene, particlesOf(positions, kRadius), 1);
}

float depthAt(const RenderResult& result, int column, int row) {
  return at(*result.layer("depth"), result.width, column, row, 0);
}

// Positions with kernel supports: h, and every third one `larger` h (particles sized apart, as splashes are).
std::vector<glm::vec4> withSupports(const std::vector<glm::vec3>& positions, float h, float larger) {
  std::vector<glm::vec4> particles;
  for (std::size_t i = 0; i < positions.size(); ++i)
    particles.emplace_back(positions[i], i % 3 == 0 ? larger * h : h);
  return particles;
}

}  // namespace

TEST(GLRaymarch, DensityGridIsConservativeOnRandomParticles) {
  LiquidParameters parameters;
  const float h = parameters.raymarch_smoothing_radius * kRadius;
  // Sparse enough that many cells hold one or two particles, where a too-small kernel weight shows.
  const auto particles = withSupports(randomPoints(1500, glm::vec3(0.0f), glm::vec3(1.2f), 3), h, 1.0f);
  const raymarch_test::GridCheck check = raymarch_test::checkDensityGrid(particles, parameters);
  EXPECT_GT(check.crossingCells, 500u) << "the iso-surface crosses many cells";
  EXPECT_LT(check.markedCells, check.cells) << "some cells are empty, else the grid skips nothing";
  EXPECT_EQ(check.missedCells, 0u) << "a cell marked 0 holds density at or above the iso-value";

  // Per-particle supports (the derived surface's): the cells are the largest support, smaller kernels fit.
  const auto mixed = withSupports(randomPoints(800, glm::vec3(0.0f), glm::vec3(1.2f), 4), h, 1.8f);
  const raymarch_test::GridCheck mixedCheck = raymarch_test::checkDensityGrid(mixed, parameters);
  EXPECT_GT(mixedCheck.crossingCells, 100u);
  EXPECT_LT(mixedCheck.markedCells, mixedCheck.cells);
  EXPECT_EQ(mixedCheck.missedCells, 0u) << "with per-particle supports";

  // The check has teeth: with b^3 below the iso-value, lone particles near a cell's corner are missed.
  parameters.raymarch_kernel_side = 0.5f;
  EXPECT_GT(raymarch_test::checkDensityGrid(particles, parameters).missedCells, 0u);
}

TEST(GLRaymarch, AdaptiveSteppingFindsTheUniformSurfaceInFewerSteps) {
  Scene scene = raymarchScene({0.0f, -1.6f, 1.0f}, {0.0f, 0.0f, 0.1f});
  scene.parameters.liquid.raymarch_resolution = "full";
  // With the default iso-value a droplet's iso-surface is its drawn sphere, so every ray that enters one hits
  // it at once and no ray crosses empty space. An iso-value above one particle's peak (droplets vanish) makes
  // the rays that enter at a droplet travel on to the pool, as the paper's splashes do; the all-ones kernel
  // of equation 4 keeps the grid conservative at any iso-value.
  scene.parameters.liquid.raymarch_iso = 1.5f;
  scene.parameters.liquid.raymarch_kernel_centre = 1.0f;
  scene.parameters.liquid.raymarch_kernel_side = 1.0f;
  const std::vector<glm::vec3> positions = poolWithDroplets();
  scene.parameters.liquid.raymarch_stepping = "uniform";
  const RenderResult uniform = render(scene, positions);
  scene.parameters.liquid.raymarch_stepping = "adaptive";
  const RenderResult adaptive = render(scene, positions);

  int both = 0, onlyOne = 0, far = 0;
  for (int row = 0; row < kHeight; ++row)
    for (int column = 0; column < kWidth; ++column) {
      const float a = depthAt(adaptive, column, row), u = depthAt(uniform, column, row);
      const bool hitA = a < 1e9f, hitU = u < 1e9f;
      if (hitA != hitU) ++onlyOne;
      if (!hitA || !hitU) continue;
      ++both;
      far += std::abs(a - u) > 0.25f * kRadius;
    }
  ASSERT_GT(both, 2000);
  // The adaptive ray jumps to D_agg after max_skip_steps, and a uniform step may pass the grazing edge of a
  // droplet: a few pixels may differ, no more.
  EXPECT_LT(far, both / 100) << "pixels whose depths differ by more than 0.25 r";
  EXPECT_LT(onlyOne, both / 100) << "pixels where only one of the two found the surface";
  const RaymarchFrameStats& a = adaptive.stats.raymarch;
  const RaymarchFrameStats& u = uniform.stats.raymarch;
  ASSERT_TRUE(a.enabled && u.enabled);
  EXPECT_EQ(a.raysCast, u.raysCast) << "full resolution: the same rays";
  // Measured 2.29 against 11.8 steps per ray (uniform steps of r / 4): the kernel bound lets the rays through
  // the vanished droplets and most of the way to the pool in one step.
  EXPECT_LT(a.totalSteps, u.totalSteps)
      << "adaptive " << a.averageStepsPerRay << " steps per ray, uniform " << u.averageStepsPerRay;
}

namespace {

struct MarchComparison {
  int both = 0;        ///< Rays that found a surface in both marches.
  int onlyOne = 0;     ///< Rays that found one in only one of them.
  int far = 0;         ///< Of `both`, rays whose surfaces lie more than 0.25 r apart in depth.
  double worst = 0.0;  ///< The largest depth difference of `both` in r.
};

// Ray for ray: each cast ray's surface (raymarch_sample_depth, 1e10 where none) in two renders of the same
// rays.
MarchComparison compareMarches(const RenderResult& a, const RenderResult& b) {
  const ImageLayer& depthA = *a.layer("raymarch_sample_depth");
  const ImageLayer& depthB = *b.layer("raymarch_sample_depth");
  MarchComparison comparison;
  for (std::size_t i = 0; i < depthA.pixels.size(); ++i) {
    const bool hitA = depthA.pixels[i] < 1e9f, hitB = depthB.pixels[i] < 1e9f;
    comparison.onlyOne += hitA != hitB;
    if (!hitA || !hitB) continue;
    ++comparison.both;
    const double difference = std::abs(double(depthA.pixels[i]) - double(depthB.pixels[i])) / kRadius;
    comparison.far += difference > 0.25;
    comparison.worst = std::max(comparison.worst, difference);
  }
  return comparison;
}

}  // namespace

TEST(GLRaymarch, AdaptiveSteppingFindsTheFineSurfaceInAQuarterOfTheUniformSteps) {
  // The named scene "pool with droplets", its particles drawn grown by 1.9 r as the examples' Mantaflow
  // domains grow them (liquid.surface_offset): D_all then stands about 1.9 r in front of the iso-surface and
  // the rays start h - r before that, as in the examples. Three marches of the same rays: uniform steps of r
  // / 10 (the converged surface, within r / 10), uniform steps of r / 4 (Xiao et al.'s baseline, within r / 4
  // of it without refinement) and the adaptive march (kernel bound, one r / 4 step beyond it, bisection).
  // (With the offset's larger kernels a density reads about four times the particles; r / 20 steps then
  // ran into llvmpipe's cap of 65,535 loop iterations per invocation on 129 long rays, r / 10 on 4.)
  Scene scene = raymarchScene({0.0f, -1.6f, 1.0f}, {0.0f, 0.0f, 0.1f});
  scene.parameters.liquid.raymarch_resolution = "full";
  scene.parameters.liquid.surface_offset = 1.9f;
  const std::vector<glm::vec3> positions = poolWithDroplets();
  liquid_test::renderer().setIntermediateLayers(true);
  scene.parameters.liquid.raymarch_stepping = "uniform";
  scene.parameters.liquid.raymarch_step = 0.1f;
  scene.parameters.liquid.raymarch_max_steps = 2048;
  const RenderResult fine = render(scene, positions);
  scene.parameters.liquid.raymarch_step = 0.25f;
  scene.parameters.liquid.raymarch_max_steps = 256;
  const RenderResult uniform = render(scene, positions);
  scene.parameters.liquid.raymarch_stepping = "adaptive";
  const RenderResult adaptive = render(scene, positions);
  liquid_test::renderer().setIntermediateLayers(false);
  for (const RenderResult* result : {&fine, &uniform, &adaptive}) {
    liquid_test::expectAllChannelsFinite(*result);
    ASSERT_NE(result->layer("raymarch_sample_depth"), nullptr);
  }

  const MarchComparison baseline = compareMarches(uniform, fine);
  const MarchComparison marched = compareMarches(adaptive, fine);
  ASSERT_GT(marched.both, 2000);
  // A step of r / 4 may pass through the grazing edge of a droplet that the fine march meets: a few rays.
  EXPECT_LT(baseline.far + baseline.onlyOne, baseline.both / 200) << "the baseline finds the fine surface";
  EXPECT_LT(marched.far + marched.onlyOne, marched.both / 200)
      << "rays where the adaptive march misses the fine surface by more than 0.25 r (worst " << marched.worst
      << " r)";

  // Measured 2.34 against 19.8 steps per ray, 5.08 against 19.8 density evaluations (refinement included) and
  // 941 against 1,867 particles read. Without the offset the rays start within about 2 r of the surface and
  // the adaptive march's least, two samples, is 2.61 against 6.36 steps.
  const RaymarchFrameStats& a = adaptive.stats.raymarch;
  const RaymarchFrameStats& u = uniform.stats.raymarch;
  ASSERT_TRUE(a.enabled && u.enabled && a.adaptiveStepping && !u.adaptiveStepping);
  EXPECT_EQ(a.raysCast, u.raysCast) << "full resolution: the same rays";
  EXPECT_EQ(u.refinementEvaluationsPerRay, 0.0) << "the baseline does not refine";
  EXPECT_DOUBLE_EQ(u.densityEvaluationsPerRay, u.averageStepsPerRay) << "each uniform step is one density";
  EXPECT_GT(a.refinementEvaluationsPerRay, 0.0);
  EXPECT_LT(4.0 * a.averageStepsPerRay, u.averageStepsPerRay)
      << "adaptive " << a.averageStepsPerRay << " steps per ray, uniform " << u.averageStepsPerRay;
  EXPECT_LT(a.densityEvaluationsPerRay, u.densityEvaluationsPerRay) << "refinement included";
  EXPECT_LT(a.particlesVisitedPerRay, u.particlesVisitedPerRay) << "the neighbour searches' work";
}

TEST(GLRaymarch, FlatWaterUsesLowerTileResolutionsThanASplash) {
  // The same camera over a flat pool and over a rough, splashing one: both cover the whole frame.
  const Scene scene = raymarchScene({0.0f, -0.5f, 1.0f}, {0.0f, 0.0f, 0.0f});
  const RenderResult flat = render(scene, block({-1.0f, -1.0f, -0.1f}, {1.0f, 1.0f, 0.0f}, kRadius));
  std::vector<glm::vec3> rough = block({-1.0f, -1.0f, -0.1f}, {1.0f, 1.0f, 0.0f}, kRadius);
  for (const glm::vec3& p : randomPoints(1500, {-1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.25f}, 11))
    rough.push_back(p);
  const RenderResult splash = render(scene, rough);
  auto raysPerLiquidTile = [](const RaymarchFrameStats& stats) {
    const double tiles = double(stats.tiles[0] + stats.tiles[1] + stats.tiles[2]);
    return (stats.tiles[0] + stats.tiles[1] / 4.0 + stats.tiles[2] / 16.0) / tiles;
  };
  const RaymarchFrameStats& f = flat.stats.raymarch;
  const RaymarchFrameStats& s = splash.stats.raymarch;
  EXPECT_EQ(f.tiles[3], 0u) << "the pool fills the frame";
  EXPECT_GT(f.tiles[2], f.tiles[0]) << "flat water: more quarter- than full-resolution tiles";
  EXPECT_GT(s.tiles[0], f.tiles[0]);
  EXPECT_LT(raysPerLiquidTile(f), 0.5 * raysPerLiquidTile(s));
  EXPECT_LT(f.raysCast, s.raysCast);
}

TEST(GLRaymarch, LoneParticleIsASphereOfItsRadius) {
  // liquid.raymarch_iso = 0.42 with h = 2 r puts a lone particle's surface at r: (1 - 0.5^2)^3 = 0.42.
  Scene scene = raymarchScene({0.0f, -1.0f, 0.0f}, {0.0f, 0.0f, 0.0f});
  liquid_test::renderer().setIntermediateLayers(true);
  const RenderResult result = render(scene, {glm::vec3(0.0f)});
  liquid_test::renderer().setIntermediateLayers(false);
  liquid_test::expectAllChannelsFinite(result);
  for (const char* layer :
       {"raymarch_steps", "raymarch_ray_spacing", "raymarch_entry_depth", "raymarch_sample_depth"})
    EXPECT_NE(result.layer(layer), nullptr) << layer;
  // The pixel centres around the image centre look straight at the particle: depth 1 - r, within the
  // refinement's resolution (a secant through a bracket of step / 2^3) plus the iso-value's rounding.
  double worst = 0.0;
  for (int row = kHeight / 2 - 1; row <= kHeight / 2; ++row)
    for (int column = kWidth / 2 - 1; column <= kWidth / 2; ++column)
      worst = std::max(worst, std::abs(double(depthAt(result, column, row)) - (1.0 - kRadius)));
  EXPECT_LT(worst, 0.03 * kRadius);
  // Every ray that passes through the iso-sphere (radius 1.0022 r) for a step or more hits it. A ray grazing
  // it for less than a step may fall between two samples, as with uniform steps: D_all, the smoothed drawn
  // sphere, can lie in front of such a chord and rays sample it in whole steps from there.
  EXPECT_GT(result.stats.raymarch.raysCast, 50u);  // the sphere is about 5 pixels in radius
  const double h = 2.0 * kRadius, iso = scene.parameters.liquid.raymarch_iso;
  const double isoRadius = h * std::sqrt(1.0 - std::cbrt(iso));
  const double step = scene.parameters.liquid.raymarch_step * kRadius;
  int throughAStep = 0;
  for (int row = 0; row < kHeight; ++row)
    for (int column = 0; column < kWidth; ++column) {
      if (at(*result.layer("raymarch_steps"), kWidth, column, row, 0) <= 0.0f) continue;  // no ray cast
      const glm::vec2 pixel(column + 0.5f, row + 0.5f);
      const glm::dvec3 near(scene.camera.worldFromPixelAndDepth(pixel, 0.5f));
      const glm::dvec3 direction =
          glm::normalize(glm::dvec3(scene.camera.worldFromPixelAndDepth(pixel, 1.5f)) - near);
      const glm::dvec3 closest = near - glm::dot(near, direction) * direction;  // the particle is the origin
      const double chord = 2.0 * std::sqrt(std::max(isoRadius * isoRadius - glm::dot(closest, closest), 0.0));
      if (chord < step) continue;
      ++throughAStep;
      EXPECT_LT(at(*result.layer("raymarch_sample_depth"), kWidth, column, row, 0), 1e9f)
          << "pixel " << column << ", " << row << ": chord " << chord / kRadius << " r";
    }
  EXPECT_GT(throughAStep, 50);
  EXPECT_GE(result.stats.raymarch.hits, unsigned(throughAStep));
}

// The derived surface (docs/mantaflow-caches.md): a Mantaflow liquid's particles are grown by
// liquid.surface_offset so a flat body stands at Mantaflow's flat offset, 0.4 r + offset above its top layer,
// and a lone drop is a sphere of Mantaflow's kernel radius (liquid.mesh_kernel_radius). The marched surface
// must stand there too. The examples' values: offset 1.91 r, kernel radius 3.16 r, spacing r / 1.1.
constexpr float kExampleOffset = 1.91f, kExampleKernelRadius = 3.16f, kMantaflowSpacing = kRadius / 1.1f;

TEST(GLRaymarch, FlatBodyStandsAtTheSurfaceOffset) {
  // A slab on Mantaflow's lattice seen from straight above: eye depth is height below the eye everywhere.
  Scene scene = raymarchScene({0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f});
  scene.camera = Camera::lookAt(kWidth, kHeight, 40.0f, {0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0});
  scene.parameters.liquid.surface_offset = kExampleOffset;
  const std::vector<glm::vec3> slab = block({-0.6f, -0.6f, -0.3f}, {0.6f, 0.6f, 0.0f}, kMantaflowSpacing);
  float top = -INFINITY;
  for (const glm::vec3& p : slab)
    top = std::max(top, p.z);
  const float expected = 1.0f - (top + (0.4f + kExampleOffset) * kRadius);
  const RenderResult result = render(scene, slab);
  liquid_test::expectAllChannelsFinite(result);
  // The 16 x 12 pixels around the centre see the flat top far from the slab's edges (the image spans about
  // 0.5 x 0.35 at the top's depth).
  double worst = 0.0;
  for (int row = kHeight / 2 - 6; row < kHeight / 2 + 6; ++row)
    for (int column = kWidth / 2 - 8; column < kWidth / 2 + 8; ++column)
      worst = std::max(worst, std::abs(double(depthAt(result, column, row)) - expected));
  EXPECT_LT(worst, 0.1 * kRadius) << "the flat top stands 0.4 r + offset above the top particles";
}

TEST(GLRaymarch, LoneDropIsMantaflowsSphere) {
  // With Mantaflow's level set a lone drop's surface is the sphere of its kernel radius r_m.
  Scene scene = raymarchScene({0.0f, -1.0f, 0.0f}, {0.0f, 0.0f, 0.0f});
  scene.parameters.liquid.surface_offset = kExampleOffset;
  scene.parameters.liquid.mesh_kernel_radius = kExampleKernelRadius;
  const RenderResult result = render(scene, {glm::vec3(0.0f)});
  liquid_test::expectAllChannelsFinite(result);
  const float radius = kExampleKernelRadius * kRadius;
  double worst = 0.0;
  for (int row = kHeight / 2 - 1; row <= kHeight / 2; ++row)
    for (int column = kWidth / 2 - 1; column <= kWidth / 2; ++column)
      worst = std::max(worst, std::abs(double(depthAt(result, column, row)) - (1.0 - radius)));
  EXPECT_LT(worst, 0.05 * kRadius);
  // Its silhouette: the pixels whose ray passes within the sphere, by the pinhole model, and no others
  // (one pixel of slack at the edge).
  const float focal = 0.5f * float(kHeight) / std::tan(glm::radians(20.0f));
  std::size_t wrong = 0, inside = 0;
  for (int row = 0; row < kHeight; ++row)
    for (int column = 0; column < kWidth; ++column) {
      const glm::vec2 offset(float(column) + 0.5f - 0.5f * kWidth, float(row) + 0.5f - 0.5f * kHeight);
      // The ray's distance from the centre at unit depth along the axis, and the sphere's angular radius.
      const float aside = glm::length(offset) / focal, sine = radius;
      const float pixelAngle = 1.0f / focal;
      const float angle = std::atan(aside), sphereAngle = std::asin(sine);
      if (std::abs(angle - sphereAngle) < 1.5f * pixelAngle) continue;
      const bool covered = depthAt(result, column, row) < 1e9f;
      inside += angle < sphereAngle;
      wrong += covered != (angle < sphereAngle);
    }
  EXPECT_GT(inside, 50u);
  EXPECT_EQ(wrong, 0u);
}

TEST(GLRaymarch, EmptyFrameAndCulledParticlesRenderWithoutNaN) {
  const Scene scene = raymarchScene({0.0f, -1.0f, 0.0f}, {0.0f, 0.0f, 0.0f});
  liquid_test::renderer().setIntermediateLayers(true);
  const RenderResult empty = render(scene, {});
  const RenderResult behind = render(scene, {glm::vec3(0.0f, -3.0f, 0.0f)});
  liquid_test::renderer().setIntermediateLayers(false);
  for (const RenderResult* result : {&empty, &behind}) {
    liquid_test::expectAllChannelsFinite(*result);
    EXPECT_EQ(result->stats.raymarch.raysCast, 0u);
    const ImageLayer& depth = *result->layer("depth");
    for (float value : depth.pixels)
      ASSERT_EQ(value, 1e10f);
  }
}

namespace {

// The named scene "one-particle-thick sheet": one layer of particles 1.6 r apart (a sheet stretched thin in a
// splash) in the plane through the origin spanned by x and (0, cos 0.7, sin 0.7), 1 x 1.
constexpr float kSheetTilt = 0.7f, kSheetSpacing = 1.6f * kRadius;

std::vector<glm::vec3> oneParticleThickSheet() {
  std::vector<glm::vec3> positions;
  for (float u = -0.5f; u <= 0.5f + 1e-6f; u += kSheetSpacing)
    for (float v = -0.5f; v <= 0.5f + 1e-6f; v += kSheetSpacing)
      positions.emplace_back(u, v * std::cos(kSheetTilt), v * std::sin(kSheetTilt));
  return positions;
}

struct SheetCoverage {
  int inside = 0;          ///< Pixels whose ray meets the sheet's interior (analytic, inset by r).
  int covered = 0;         ///< Of those, pixels with liquid.
  double medianAngle = 0;  ///< Median angle between the rendered normal and the plane's, degrees.
};

SheetCoverage sheetCoverage(const Scene& scene, const RenderResult& result) {
  const Camera& camera = scene.camera;
  const glm::dvec3 planeNormal(0.0, -std::sin(kSheetTilt), std::cos(kSheetTilt));
  const glm::dvec3 along(0.0, std::cos(kSheetTilt), std::sin(kSheetTilt));
  const glm::dvec3 eye(camera.worldFromCamera[3]);
  const double tanHalfY = std::tan(glm::radians(double(camera.fovYDegrees)) * 0.5);
  const double tanHalfX = tanHalfY * double(camera.width) / double(camera.height);
  const double last =
      -0.5 + std::floor(1.0 / kSheetSpacing + 1e-6) * kSheetSpacing;  // the last row's coordinate
  SheetCoverage coverage;
  std::vector<double> angles;
  for (int row = 0; row < camera.height; ++row)
    for (int column = 0; column < camera.width; ++column) {
      const glm::dvec3 cameraRay((column + 0.5) / camera.width * 2.0 - 1.0,
                                 1.0 - (row + 0.5) / camera.height * 2.0, -1.0);
      const glm::dvec3 ray =
          glm::dmat3(camera.worldFromCamera) * (cameraRay * glm::dvec3(tanHalfX, tanHalfY, 1.0));
      const double t = -glm::dot(eye, planeNormal) / glm::dot(ray, planeNormal);
      const glm::dvec3 hit = eye + t * ray;
      const double u = hit.x, v = glm::dot(hit, along);
      if (t <= 0.0 || u < -0.5 + kRadius || u > last - kRadius || v < -0.5 + kRadius || v > last - kRadius)
        continue;
      ++coverage.inside;
      if (at(*result.layer("depth"), camera.width, column, row, 0) > 1e9f) continue;
      ++coverage.covered;
      const glm::dvec3 normal(at(*result.layer("normal"), camera.width, column, row, 0),
                              at(*result.layer("normal"), camera.width, column, row, 1),
                              at(*result.layer("normal"), camera.width, column, row, 2));
      angles.push_back(
          glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(normal), planeNormal), -1.0, 1.0))));
    }
  if (!angles.empty()) {
    std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
    coverage.medianAngle = angles[angles.size() / 2];
  }
  return coverage;
}

}  // namespace

TEST(GLRaymarch, OneParticleThickSheetIsKeptWherePlaneFittingLosesIt) {
  Scene scene = raymarchScene({0.3f, -2.0f, 0.9f}, {0.0f, 0.0f, 0.0f});
  const std::vector<glm::vec3> sheet = oneParticleThickSheet();
  const SheetCoverage marched = sheetCoverage(scene, render(scene, sheet));
  // With Yu and Turk's N_epsilon as they give it (25): the sheet's particles have fewer neighbours.
  scene.parameters.liquid.anisotropy_min_neighbour_fraction = 0.0f;
  scene.parameters.liquid.surface = "screen";
  const SheetCoverage spheres = sheetCoverage(scene, render(scene, sheet));
  scene.parameters.liquid.layers = "merged";  // every particle an aggregate, plane-fit smoothed
  const SheetCoverage planeFit = sheetCoverage(scene, render(scene, sheet));
  // With N_epsilon relative to the frame's full neighbourhood (the default), the sheet's particles are its
  // full neighbourhood: they are flat ellipsoids, and the screen-space surface keeps the sheet too.
  scene.parameters.liquid.anisotropy_min_neighbour_fraction = 0.25f;
  scene.parameters.liquid.layers = "split";
  const SheetCoverage relative = sheetCoverage(scene, render(scene, sheet));

  ASSERT_GT(marched.inside, 1000);
  EXPECT_GT(marched.covered, 0.97 * marched.inside) << "the marched sheet is closed";
  EXPECT_LT(marched.medianAngle, 10.0) << "and has the plane's normal";
  // The screen-space surface loses it: plane-fit aggregates (under-sampled, so small spheres) leave most of
  // it open; as splashes it is a curtain of spheres whose normals are the spheres'.
  EXPECT_LT(planeFit.covered, 0.6 * planeFit.inside);
  EXPECT_GT(spheres.medianAngle, 25.0);
  EXPECT_GT(relative.covered, 0.97 * relative.inside);
  EXPECT_LT(relative.medianAngle, 10.0);
}

TEST(GLRaymarch, FlatWaterCloseUpHasTheFlatNormal) {
  // A slab on Mantaflow's lattice seen at 35° from close by, its grown particles some 60 pixels across:
  // N_screen comes from D_all smoothed by liquid.smoothing. Green's separable bilateral filter (the paper's
  // filter, `bilateral`) streaks along its second pass where the particles are large on screen; the default
  // plane fit keeps the slab's own normal. The drop example's close-up camera measured 27° against 4° the
  // same way.
  Scene scene = raymarchScene({0.0f, -0.35f, 0.25f}, {0.0f, 0.0f, 0.0f});
  scene.parameters.liquid.surface_offset = kExampleOffset;
  const std::vector<glm::vec3> slab = block({-0.8f, -0.8f, -0.2f}, {0.8f, 0.8f, 0.0f}, kMantaflowSpacing);
  const auto medianNormalError = [&](const RenderResult& result) {
    liquid_test::expectAllChannelsFinite(result);
    std::vector<double> degrees;
    const ImageLayer& normal = *result.layer("normal");
    for (int row = kHeight / 4; row < 3 * kHeight / 4; ++row)
      for (int column = kWidth / 4; column < 3 * kWidth / 4; ++column) {
        const glm::dvec3 n(at(normal, kWidth, column, row, 0), at(normal, kWidth, column, row, 1),
                           at(normal, kWidth, column, row, 2));
        degrees.push_back(glm::degrees(std::acos(std::clamp(glm::normalize(n).z, -1.0, 1.0))));
      }
    std::nth_element(degrees.begin(), degrees.begin() + degrees.size() / 2, degrees.end());
    return degrees[degrees.size() / 2];
  };
  const double planeFit = medianNormalError(render(scene, slab));
  scene.parameters.liquid.smoothing = "bilateral";
  const double bilateral = medianNormalError(render(scene, slab));
  std::cout << "median normal error of the marched slab: plane fit " << planeFit << "°, bilateral "
            << bilateral << "°\n";
  EXPECT_LT(planeFit, 2.0);
  EXPECT_LT(planeFit, 0.5 * bilateral);
}
