#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "SharedViewChecks.h"
#include "prep/Anisotropy.h"
#include "prep/FrameLiquidCache.h"
#include "prep/LiquidPreparation.h"
#include "spindrift/Parameters.h"

namespace spindrift {
namespace {

// Lengths are in units of a small particle radius, so that nothing passes only because r happens to be 1.
constexpr float kRadius = 0.05f;

Camera testCamera() {
  return Camera::lookAt(64, 64, 60.0f, {0, -10, 0}, {0, 0, 0}, {0, 0, 1});
}

// Yu and Turk's shapes as they are: liquid.reach_radius's growth is tested on its own
// (ReachRadiusPutsAFlatFaceWhereTheParticlesSpheresReach).
LiquidParameters layers(const char* mode) {
  LiquidParameters parameters;
  parameters.layers = mode;
  parameters.reach_radius = false;
  return parameters;
}

void addLiquid(Particles& particles, const glm::vec3& position, float radius = kRadius) {
  particles.append(position, radius, ParticleKind::Liquid, 0.0f, {});
}

// A cube of `side`^3 particles centred on `centre`, `spacing` radii apart, jittered by up to `jitter` radii.
void addBlock(Particles& particles, const glm::vec3& centre, int side, float spacing, float jitter = 0.0f,
              unsigned seed = 1) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> offset(-jitter, jitter);
  const float half = 0.5f * float(side - 1);
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k) {
        const glm::vec3 lattice = glm::vec3(float(i) - half, float(j) - half, float(k) - half) * spacing;
        const glm::vec3 jittered = lattice + glm::vec3(offset(random), offset(random), offset(random));
        addLiquid(particles, centre + jittered * kRadius);
      }
}

// The principal semi-axes of an instance (1 / length of each row of the inverse axes matrix) and directions.
struct Axes {
  glm::vec3 semiAxes;
  glm::vec3 directions[3];
};
Axes axesOf(const EllipsoidInstance& instance) {
  Axes axes;
  for (int k = 0; k < 3; ++k) {
    const glm::vec3 row(instance.inverseAxesRows[k]);
    axes.semiAxes[k] = 1.0f / glm::length(row);
    axes.directions[k] = row * axes.semiAxes[k];
  }
  return axes;
}

bool allFinite(const std::vector<EllipsoidInstance>& instances) {
  for (const EllipsoidInstance& instance : instances) {
    const float* values = &instance.centreAndBoundingRadius.x;
    for (int v = 0; v < 16; ++v)
      if (!std::isfinite(values[v])) return false;
  }
  return true;
}

void expectWellFormed(const LiquidPreparation& preparation) {
  EXPECT_TRUE(allFinite(preparation.splashes));
  EXPECT_TRUE(allFinite(preparation.aggregates));
  EXPECT_TRUE(std::isfinite(preparation.totalMilliseconds));
}

// The instance whose centre is nearest `position` (centres are the particles' with the default smoothing 0).
const EllipsoidInstance* instanceAt(const std::vector<EllipsoidInstance>& instances,
                                    const glm::vec3& position) {
  for (const EllipsoidInstance& instance : instances)
    if (glm::length(glm::vec3(instance.centreAndBoundingRadius) - position) < 1e-6f) return &instance;
  return nullptr;
}

void expectSphere(const EllipsoidInstance& instance, float radius) {
  EXPECT_NEAR(instance.centreAndBoundingRadius.w, radius, 1e-6f);
  for (int k = 0; k < 3; ++k)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(instance.inverseAxesRows[k][c], k == c ? 1.0f / radius : 0.0f, 1e-3f);
}

TEST(LiquidPreparation, ColinearCluster) {
  const glm::vec3 direction = glm::normalize(glm::vec3(1, 2, 3));
  Particles particles;
  for (int i = -30; i <= 30; ++i)
    addLiquid(particles, direction * (float(i) * 0.1f * kRadius));
  const LiquidPreparation preparation = prepareLiquid(particles, testCamera(), layers("merged"));
  expectWellFormed(preparation);
  const EllipsoidInstance* middle = instanceAt(preparation.aggregates, glm::vec3(0.0f));
  ASSERT_NE(middle, nullptr);
  const Axes axes = axesOf(*middle);
  const int longest = int(std::max_element(&axes.semiAxes[0], &axes.semiAxes[0] + 3) - &axes.semiAxes[0]);
  EXPECT_GT(std::abs(glm::dot(axes.directions[longest], direction)), 0.999f);
  // A line's spread along it exceeds the rest spread: bounded by 1.2 r, and the others clamped by k_r = 4.
  EXPECT_NEAR(axes.semiAxes[longest], 1.2f * kRadius, 1e-4f);
  for (int k = 0; k < 3; ++k)
    if (k != longest) EXPECT_NEAR(axes.semiAxes[k], 0.3f * kRadius, 1e-4f);
}

TEST(LiquidPreparation, CoplanarCluster) {
  const glm::vec3 normal = glm::normalize(glm::vec3(0.3f, -1.0f, 0.5f));
  const glm::vec3 tangent = glm::normalize(glm::cross(normal, glm::vec3(0, 0, 1)));
  const glm::vec3 bitangent = glm::cross(normal, tangent);
  Particles particles;
  for (int i = -15; i <= 15; ++i)
    for (int j = -15; j <= 15; ++j)
      addLiquid(particles, (float(i) * tangent + float(j) * bitangent) * (0.4f * kRadius));
  const LiquidPreparation preparation = prepareLiquid(particles, testCamera(), layers("split"));
  expectWellFormed(preparation);
  // A sheet denser than the rest density is aggregated liquid, flattened along its normal.
  const EllipsoidInstance* middle = instanceAt(preparation.aggregates, glm::vec3(0.0f));
  ASSERT_NE(middle, nullptr);
  const Axes axes = axesOf(*middle);
  const int shortest = int(std::min_element(&axes.semiAxes[0], &axes.semiAxes[0] + 3) - &axes.semiAxes[0]);
  EXPECT_GT(std::abs(glm::dot(axes.directions[shortest], normal)), 0.999f);
  for (int k = 0; k < 3; ++k) {
    if (k == shortest) continue;
    // In the plane: the weighted spread of a disc, 0.179 R^2 per axis, over the rest spread 0.15 R^2.
    EXPECT_NEAR(axes.semiAxes[k] / kRadius, 0.179f / 0.15f, 0.03f);
    EXPECT_NEAR(axes.semiAxes[shortest] * 4.0f, axes.semiAxes[k], 1e-4f);
  }
}

TEST(LiquidPreparation, SingleNeighbour) {
  Particles particles;
  addLiquid(particles, {0, 0, 0});
  addLiquid(particles, {kRadius, 0, 0});
  const LiquidPreparation split = prepareLiquid(particles, testCamera(), layers("split"));
  expectWellFormed(split);
  ASSERT_EQ(split.splashes.size(), 2u);
  EXPECT_TRUE(split.aggregates.empty());
  for (const EllipsoidInstance& splash : split.splashes)
    expectSphere(splash, kRadius);

  // Too few neighbours for a covariance: Yu and Turk's isotropic k_n r.
  const LiquidPreparation merged = prepareLiquid(particles, testCamera(), layers("merged"));
  ASSERT_EQ(merged.aggregates.size(), 2u);
  for (const EllipsoidInstance& aggregate : merged.aggregates)
    expectSphere(aggregate, 0.5f * kRadius);
}

TEST(LiquidPreparation, CoincidentParticles) {
  Particles particles;
  for (int i = 0; i < 40; ++i)
    addLiquid(particles, {0.1f, 0.2f, 0.3f});
  for (const char* mode : {"split", "merged"}) {
    const LiquidPreparation preparation = prepareLiquid(particles, testCamera(), layers(mode));
    expectWellFormed(preparation);
    EXPECT_EQ(preparation.splashes.size() + preparation.aggregates.size(), 40u);
    for (const auto* instances : {&preparation.splashes, &preparation.aggregates})
      for (const EllipsoidInstance& instance : *instances) {
        EXPECT_GT(instance.centreAndBoundingRadius.w, 0.0f);
        EXPECT_LE(instance.centreAndBoundingRadius.w, 1.2f * kRadius);
      }
  }
}

TEST(LiquidPreparation, IsolatedParticleIsASplash) {
  Particles particles;
  addBlock(particles, {0, 0, 0}, 16, 0.9f);
  const glm::vec3 isolated(20.0f * kRadius, 0.0f, 0.0f);
  addLiquid(particles, isolated);
  const LiquidPreparation preparation = prepareLiquid(particles, testCamera(), layers("split"));
  expectWellFormed(preparation);
  const EllipsoidInstance* splash = instanceAt(preparation.splashes, isolated);
  ASSERT_NE(splash, nullptr);
  expectSphere(*splash, kRadius);
  // Only the isolated particle and the block's corners (an eighth of a neighbourhood) are below 0.2.
  EXPECT_LE(preparation.splashes.size(), 9u);
  EXPECT_EQ(instanceAt(preparation.splashes, glm::vec3(0.45f * kRadius)), nullptr);
}

TEST(LiquidPreparation, InteriorOfABlockIsAggregateAndIsotropic) {
  Particles particles;
  addBlock(particles, {0, 0, 0}, 20, 0.9f, 0.1f);
  const LiquidPreparation preparation = prepareLiquid(particles, testCamera(), layers("split"));
  expectWellFormed(preparation);
  // Particles at least a neighbourhood (2.5 r, about 3 spacings) inside: 14^3 of 20^3.
  EXPECT_GE(preparation.isotropicInterior, std::size_t(14 * 14 * 14 * 0.9));
  std::size_t spheresOfRadiusR = 0;
  for (const EllipsoidInstance& aggregate : preparation.aggregates) {
    const Axes axes = axesOf(aggregate);
    spheresOfRadiusR += std::abs(axes.semiAxes.x - kRadius) < 1e-6f &&
                        std::abs(axes.semiAxes.y - kRadius) < 1e-6f &&
                        std::abs(axes.semiAxes.z - kRadius) < 1e-6f;
  }
  EXPECT_EQ(spheresOfRadiusR, preparation.isotropicInterior);
  // A face particle is flattened along the face's normal (here +y, towards the camera).
  const glm::vec3 faceCentre(0.45f * kRadius, -9.5f * 0.9f * kRadius, 0.45f * kRadius);
  const EllipsoidInstance* face = nullptr;
  float nearest = 1e9f;
  for (const EllipsoidInstance& aggregate : preparation.aggregates) {
    const float distance = glm::length(glm::vec3(aggregate.centreAndBoundingRadius) - faceCentre);
    if (distance < nearest) nearest = distance, face = &aggregate;
  }
  ASSERT_NE(face, nullptr);
  const Axes axes = axesOf(*face);
  const int shortest = int(std::min_element(&axes.semiAxes[0], &axes.semiAxes[0] + 3) - &axes.semiAxes[0]);
  EXPECT_GT(std::abs(axes.directions[shortest].y), 0.9f);
  EXPECT_LT(axes.semiAxes[shortest], 0.7f * kRadius);
}

TEST(LiquidPreparation, BoundedByMaxEllipsoidScale) {
  std::mt19937 random(7);
  std::normal_distribution<float> gaussian;
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int cluster = 0; cluster < 20; ++cluster) {
    Particles particles;
    const int count = 5 + int(uniform(random) * 400.0f);
    // Stretched Gaussian blobs, from a few radii to needles and pancakes.
    const glm::vec3 stretch = glm::vec3(uniform(random), uniform(random), uniform(random)) * 4.0f + 0.01f;
    for (int i = 0; i < count; ++i)
      addLiquid(particles,
                glm::vec3(gaussian(random), gaussian(random), gaussian(random)) * stretch * kRadius);
    for (const char* mode : {"split", "merged"}) {
      const LiquidPreparation preparation = prepareLiquid(particles, testCamera(), layers(mode));
      expectWellFormed(preparation);
      ASSERT_EQ(preparation.splashes.size() + preparation.aggregates.size(), std::size_t(count));
      for (const EllipsoidInstance& aggregate : preparation.aggregates) {
        const Axes axes = axesOf(aggregate);
        for (int k = 0; k < 3; ++k) {
          EXPECT_LE(axes.semiAxes[k], 1.2f * kRadius * 1.0001f);
          // The longest is at least k_n r = 0.5 r, and k_r = 4 bounds the ratio.
          EXPECT_GE(axes.semiAxes[k], 0.5f * kRadius / 4.0f * 0.9999f);
          for (int other = 0; other < k; ++other)
            EXPECT_NEAR(glm::dot(axes.directions[k], axes.directions[other]), 0.0f, 1e-4f);
        }
        EXPECT_NEAR(aggregate.centreAndBoundingRadius.w,
                    std::max({axes.semiAxes.x, axes.semiAxes.y, axes.semiAxes.z}), 1e-5f * kRadius);
      }
    }
  }
}

TEST(LiquidPreparation, InverseAxesMapTheEllipsoidToTheUnitSphere) {
  const glm::vec3 axes[3] = {glm::normalize(glm::vec3(1, 1, 0)), glm::normalize(glm::vec3(-1, 1, 1)),
                             glm::normalize(glm::vec3(1, -1, 2))};
  const glm::vec3 semiAxes(0.06f, 0.02f, 0.035f);
  const glm::vec3 centre(1, 2, 3);
  const EllipsoidInstance instance = ellipsoidInstance(centre, axes, semiAxes);
  EXPECT_FLOAT_EQ(instance.centreAndBoundingRadius.w, 0.06f);
  std::mt19937 random(3);
  std::normal_distribution<float> gaussian;
  for (int sample = 0; sample < 100; ++sample) {
    const glm::vec3 unit = glm::normalize(glm::vec3(gaussian(random), gaussian(random), gaussian(random)));
    const glm::vec3 onEllipsoid = centre + unit.x * semiAxes.x * axes[0] + unit.y * semiAxes.y * axes[1] +
                                  unit.z * semiAxes.z * axes[2];
    const glm::vec3 offset = onEllipsoid - centre;
    const glm::vec3 mapped(glm::dot(glm::vec3(instance.inverseAxesRows[0]), offset),
                           glm::dot(glm::vec3(instance.inverseAxesRows[1]), offset),
                           glm::dot(glm::vec3(instance.inverseAxesRows[2]), offset));
    EXPECT_NEAR(glm::length(mapped), 1.0f, 1e-4f);
  }
}

TEST(LiquidPreparation, ParticlesBehindTheCameraAndStraddlingTheNearPlane) {
  Camera camera = Camera::lookAt(64, 64, 60.0f, {0, 0, 0}, {0, 1, 0}, {0, 0, 1});
  camera.nearClip = 0.1f;
  Particles particles;
  addLiquid(particles, {0, -5, 0});                     // Behind the camera.
  addLiquid(particles, {0, 0.1f + 0.5f * kRadius, 0});  // Straddles the near plane.
  addLiquid(particles, {0, 0.1f - 0.5f * kRadius, 0});  // Its centre is in front of the near plane.
  addLiquid(particles, {0, 5, 0});                      // In view.
  addLiquid(particles, {50, 5, 0});                     // Beside the frustum.
  addLiquid(particles, {0, 2000, 0});                   // Beyond the far plane.
  const LiquidPreparation preparation = prepareLiquid(particles, camera, layers("merged"));
  expectWellFormed(preparation);
  EXPECT_EQ(preparation.aggregates.size(), 3u);
  EXPECT_EQ(preparation.culled, 3u);
}

TEST(LiquidPreparation, OffScreenNeighboursShapeVisibleParticles) {
  // A block straddling the right edge of the view: a visible particle at the edge has neighbours on both
  // sides, so the particles at the edge are interior, not a surface.
  const Camera camera = testCamera();
  const float edgeX = 10.0f * std::tan(glm::radians(30.0f));
  Particles particles;
  addBlock(particles, {edgeX, 0, 0}, 20, 0.9f);
  const LiquidPreparation preparation = prepareLiquid(particles, camera, layers("split"));
  expectWellFormed(preparation);
  EXPECT_GT(preparation.culled, 0u);
  std::size_t nearTheEdge = 0, anisotropicNearTheEdge = 0;
  for (const EllipsoidInstance& aggregate : preparation.aggregates) {
    const glm::vec3 centre(aggregate.centreAndBoundingRadius);
    const bool deepInY = std::abs(centre.y) < 5.0f * kRadius && std::abs(centre.z) < 5.0f * kRadius;
    if (!deepInY || centre.x < edgeX - 4.0f * kRadius) continue;
    ++nearTheEdge;
    anisotropicNearTheEdge += aggregate.centreAndBoundingRadius.w != kRadius;
  }
  EXPECT_GT(nearTheEdge, 100u);
  EXPECT_EQ(anisotropicNearTheEdge, 0u);
}

TEST(LiquidPreparation, ViewsSharingAFrameCacheShapeEachParticleOnceAndGetWhatTheyGetAlone) {
  // A jittered block with drops over it (liquid.reach_radius and smoothing at their defaults), seen obliquely
  // and from above (both see every particle: the second reuses the first's shapes) and from close by (it
  // culls, so it shapes its own): every view's ellipsoids are bit for bit those it gets alone, in any order.
  Particles particles;
  addBlock(particles, {0, 0, 0}, 10, 1.0f, 0.3f, 5);
  for (int i = 0; i < 6; ++i)
    addLiquid(particles, glm::vec3(0.1f * float(i) - 0.25f, 0.05f, 0.5f + 0.07f * float(i)));
  LiquidParameters parameters;
  const Camera views[] = {Camera::lookAt(64, 64, 60.0f, {2, -3, 2}, {0, 0, 0}, {0, 0, 1}),
                          Camera::lookAt(64, 64, 60.0f, {0.01f, 0.02f, 4}, {0, 0, 0}, {0, 1, 0}),
                          Camera::lookAt(64, 64, 30.0f, {0.6f, -0.3f, 0.2f}, {0.3f, 0, 0}, {0, 0, 1})};
  const std::vector<LiquidPreparation> alone = shared_views::expectSharedViewsGetWhatTheyGetAlone(
      particles, parameters, views,
      [&](const LiquidPreparation& shared, const LiquidPreparation& single, const FrameLiquidCache& frame,
          int view, const std::vector<int>& order) {
        EXPECT_EQ(shared.fullNeighbours, single.fullNeighbours);
        // The culling view leaves the memory as it was; a whole view has shaped every particle into it.
        EXPECT_EQ(frame.shapes.remembered(), view == 2 && order.front() == 2 ? 0u : particles.size())
            << "view " << view;
      });
  EXPECT_GT(alone[0].splashes.size(), 0u);
}

// A jittered block with four drops over it: aggregates, splashes and Mantaflow's surface all take part.
Particles jitteredBlockWithDrops() {
  Particles particles;
  addBlock(particles, {0, 0, 0}, 8, 1.0f, 0.3f, 7);
  for (int i = 0; i < 4; ++i)
    addLiquid(particles, glm::vec3(0.1f * float(i) - 0.2f, 0.05f, 0.45f + 0.07f * float(i)));
  return particles;
}

Camera obliqueCamera() {
  return Camera::lookAt(64, 64, 60.0f, {2, -3, 2}, {0, 0, 0}, {0, 0, 1});
}

TEST(LiquidPreparation, ShapesAreKeptForTheNextFrameOnlyWhileItsParticlesAndParametersAreTheSame) {
  // Frames of a block with drops over it, each seen by another camera (a viewport orbiting a paused frame),
  // with and without Mantaflow's surface: a frame that keeps the one before's cache gets bit for bit what it
  // gets alone, and a moved particle, a changed parameter or liquid.reuse_shapes false forgets it. A frame
  // keeps its shapes where its particles are the frame before's, or where other views (lights) share them.
  const Particles particles = jitteredBlockWithDrops();
  const Camera oblique = obliqueCamera();
  const Camera above = Camera::lookAt(64, 64, 60.0f, {0.01f, 0.02f, 4}, {0, 0, 0}, {0, 1, 0});
  const std::string keptNone = "the frame before kept none (the same particles: this frame keeps them)";
  for (const float meshKernelRadius : {0.0f, 2.0f}) {
    LiquidParameters parameters;
    parameters.mesh_kernel_radius = meshKernelRadius;
    LiquidCacheAcrossFrames across;
    // `remembered`: the shapes the cache holds before the frame's preparation; -1: no cache for the frame.
    const auto expectFrame = [&](const Particles& frameParticles, const LiquidParameters& frameParameters,
                                 const Camera& camera, bool lights, const std::string& whyNotKept,
                                 int remembered) {
      FrameLiquidCache* cache = across.forFrame(frameParticles, frameParameters, lights);
      EXPECT_EQ(across.whyNotKept(), whyNotKept);
      EXPECT_EQ(cache ? int(cache->shapes.remembered()) : -1, remembered) << whyNotKept;
      const LiquidPreparation kept = prepareLiquid(frameParticles, camera, frameParameters, cache);
      const LiquidPreparation alone = prepareLiquid(frameParticles, camera, frameParameters);
      EXPECT_TRUE(shared_views::sameInstances(kept.aggregates, alone.aggregates)) << whyNotKept;
      EXPECT_TRUE(shared_views::sameInstances(kept.splashes, alone.splashes)) << whyNotKept;
      EXPECT_FALSE(kept.aggregates.empty());
    };
    SCOPED_TRACE(meshKernelRadius);
    const int all = int(particles.size());
    expectFrame(particles, parameters, oblique, false, "no frame before", -1);
    expectFrame(particles, parameters, above, false, keptNone, 0);
    expectFrame(particles, parameters, oblique, false, "", all);
    expectFrame(particles, parameters, above, false, "", all);
    Particles moved = particles;
    moved.positions[5].z += 1e-4f;
    expectFrame(moved, parameters, above, true, "the particles changed", 0);
    expectFrame(moved, parameters, oblique, false, "", all);
    LiquidParameters rounder = parameters;
    rounder.anisotropy_isotropic_scale *= 1.1f;
    expectFrame(moved, rounder, above, false, "a shaping parameter changed", -1);
    expectFrame(moved, rounder, oblique, false, keptNone, 0);
    expectFrame(moved, rounder, above, false, "", all);
    LiquidParameters anew = rounder;
    anew.reuse_shapes = false;
    expectFrame(moved, anew, oblique, false, "liquid.reuse_shapes is false", -1);
    expectFrame(moved, anew, oblique, true, "liquid.reuse_shapes is false", 0);
    expectFrame(moved, rounder, oblique, false, "no frame before", -1);
  }
}

// Another valid value of a parameter: a Bool flipped, a number moved within its range, another choice.
nlohmann::json otherValue(const ParameterInfo& info, const nlohmann::json& current) {
  if (info.type == "Bool") return !current.get<bool>();
  if (info.type == "Choice") {
    for (const std::string& choice : info.choices)
      if (choice != current.get<std::string>()) return choice;
  }
  const auto moved = [&](double value) {
    const double up = value != 0.0 ? value * 1.2 : std::min(info.maximum, info.minimum + 0.5);
    return up <= info.maximum ? up : value * 0.8;
  };
  if (info.type == "Int") {
    const int value = current.get<int>();
    return value + 1 <= int(info.maximum) ? value + 1 : value - 1;
  }
  if (info.type == "Float") return moved(current.get<double>());
  nlohmann::json vector = nlohmann::json::array();  // Color, Vec3
  for (const nlohmann::json& component : current)
    vector.push_back(moved(component.get<double>()));
  return vector;
}

TEST(LiquidPreparation, OnlyTheShapingParametersForgetTheKeptShapes) {
  // Every liquid parameter outside shapingParameterKeys() leaves the kept shapes valid: with it changed, a
  // frame that keeps the frame before's cache gets bit for bit what it gets alone. Each of those keys,
  // changed, forgets them.
  const Particles particles = jitteredBlockWithDrops();
  const Camera camera = obliqueCamera();
  const std::vector<std::string>& shaping = shapingParameterKeys();
  std::size_t checked = 0;
  for (const float meshKernelRadius : {0.0f, 2.0f})
    for (const ParameterInfo& info : parameterTable()) {
      if (info.key.rfind("liquid.", 0) != 0) continue;
      Parameters base;
      base.liquid.mesh_kernel_radius = meshKernelRadius;
      Parameters changed = base;
      setParameter(changed, info.key, otherValue(info, getParameter(base, info.key)));
      const bool shapes = std::find(shaping.begin(), shaping.end(), info.key) != shaping.end();
      EXPECT_EQ(sameShapingParameters(base.liquid, changed.liquid), !shapes) << info.key;
      if (shapes) continue;
      LiquidCacheAcrossFrames across;
      across.forFrame(particles, base.liquid, false);
      prepareLiquid(particles, camera, base.liquid, across.forFrame(particles, base.liquid, false));
      FrameLiquidCache* kept = across.forFrame(particles, changed.liquid, false);
      EXPECT_EQ(across.whyNotKept(), "") << info.key;
      ASSERT_NE(kept, nullptr) << info.key;
      ASSERT_GT(kept->shapes.remembered(), 0u) << info.key;
      const LiquidPreparation reused = prepareLiquid(particles, camera, changed.liquid, kept);
      const LiquidPreparation alone = prepareLiquid(particles, camera, changed.liquid);
      EXPECT_TRUE(shared_views::sameInstances(reused.aggregates, alone.aggregates)) << info.key;
      EXPECT_TRUE(shared_views::sameInstances(reused.splashes, alone.splashes)) << info.key;
      ++checked;
    }
  EXPECT_GT(checked, 60u) << "the liquid group's other parameters, twice";
}

TEST(LiquidPreparation, ShapeMemoryForgetsAParticleThatMoved) {
  ShapeMemory memory;
  memory.reset(2);
  ViewlessShape shape;
  shape.density = 3.0f;
  memory.remember(1, {1, 2, 3}, 0.5f, shape);
  ASSERT_NE(memory.find(1, {1, 2, 3}, 0.5f), nullptr);
  EXPECT_EQ(memory.find(1, {1, 2, 3}, 0.5f)->density, 3.0f);
  EXPECT_EQ(memory.find(1, {1, 2, 3.001f}, 0.5f), nullptr);
  EXPECT_EQ(memory.find(1, {1, 2, 3}, 0.6f), nullptr);
  EXPECT_EQ(memory.find(0, {0, 0, 0}, -1.0f), nullptr) << "an empty entry matches nothing";
  EXPECT_EQ(memory.find(2, {1, 2, 3}, 0.5f), nullptr) << "out of range";
  EXPECT_EQ(memory.remembered(), 1u);
}

TEST(LiquidPreparation, EmptyInput) {
  for (const char* mode : {"split", "merged"}) {
    const LiquidPreparation none = prepareLiquid(Particles{}, testCamera(), layers(mode));
    EXPECT_TRUE(none.splashes.empty());
    EXPECT_TRUE(none.aggregates.empty());
    EXPECT_EQ(none.culled, 0u);
    EXPECT_EQ(none.isotropicInterior, 0u);
    Particles foamOnly;
    foamOnly.append({0, 0, 0}, kRadius, ParticleKind::Foam, 1.0f, {});
    const LiquidPreparation foam = prepareLiquid(foamOnly, testCamera(), layers(mode));
    EXPECT_TRUE(foam.splashes.empty());
    EXPECT_TRUE(foam.aggregates.empty());
    EXPECT_EQ(foam.culled, 0u);
  }
}

TEST(LiquidPreparation, MergedLayersPutEverythingInAggregates) {
  Particles particles;
  addBlock(particles, {0, 0, 0}, 12, 0.9f, 0.1f);
  for (int i = 0; i < 10; ++i)
    addLiquid(particles, {float(i) * 4.0f * kRadius, 0, 30.0f * kRadius});
  const LiquidPreparation split = prepareLiquid(particles, testCamera(), layers("split"));
  const LiquidPreparation merged = prepareLiquid(particles, testCamera(), layers("merged"));
  expectWellFormed(split);
  expectWellFormed(merged);
  EXPECT_GE(split.splashes.size(), 10u);
  EXPECT_TRUE(merged.splashes.empty());
  EXPECT_EQ(merged.aggregates.size(), particles.size());
  EXPECT_EQ(merged.isotropicInterior, split.isotropicInterior);
}

// liquid.reach_radius: a block on a lattice 1.33 r apart (a Blender particle grid's spacing). Yu and Turk's
// shapes flatten the top face's particles along +z, so without the growth the face stands well inside the
// particles' spheres; grown until each anisotropic aggregate's shortest semi-axis reaches r, it stands r
// above the top particles' centres, as their spheres do. No aggregate is grown past the bound the frustum and
// the lights' views allow for (largestSurfaceOffset), and interior spheres keep radius r.
TEST(LiquidPreparation, ReachRadiusPutsAFlatFaceWhereTheParticlesSpheresReach) {
  Particles particles;
  const int side = 12;
  const float spacing = 1.33f;
  addBlock(particles, {0, 0, 0}, side, spacing);
  const float topCentres = 0.5f * float(side - 1) * spacing * kRadius;
  const auto faceAboveCentres = [&](const LiquidPreparation& preparation) {
    float top = -1e30f;
    for (const EllipsoidInstance& aggregate : preparation.aggregates) {
      const glm::vec3 centre(aggregate.centreAndBoundingRadius);
      if (std::abs(centre.x) > 2.0f * spacing * kRadius || std::abs(centre.y) > 2.0f * spacing * kRadius)
        continue;
      const Axes axes = axesOf(aggregate);
      float support = 0.0f;  // how far the ellipsoid reaches along +z
      for (int k = 0; k < 3; ++k)
        support += std::pow(axes.semiAxes[k] * axes.directions[k].z, 2.0f);
      top = std::max(top, centre.z + std::sqrt(support));
    }
    return (top - topCentres) / kRadius;
  };
  LiquidParameters parameters = layers("split");
  const LiquidPreparation yuAndTurk = prepareLiquid(particles, testCamera(), parameters);
  parameters.reach_radius = true;
  const LiquidPreparation reached = prepareLiquid(particles, testCamera(), parameters);
  expectWellFormed(reached);
  ASSERT_EQ(reached.aggregates.size(), yuAndTurk.aggregates.size());
  std::printf("flat face above the top centres: %.3f r as Yu and Turk shape it, %.3f r reached\n",
              faceAboveCentres(yuAndTurk), faceAboveCentres(reached));
  EXPECT_LT(faceAboveCentres(yuAndTurk), 0.6f);
  EXPECT_NEAR(faceAboveCentres(reached), 1.0f, 0.02f);
  const float largest = std::max(1.0f, parameters.max_ellipsoid_scale) + largestSurfaceOffset(parameters);
  std::size_t grownPastYuAndTurk = 0;
  for (const EllipsoidInstance& aggregate : reached.aggregates) {
    const Axes axes = axesOf(aggregate);
    const float shortest = std::min({axes.semiAxes.x, axes.semiAxes.y, axes.semiAxes.z});
    const float longest = std::max({axes.semiAxes.x, axes.semiAxes.y, axes.semiAxes.z});
    // The block's corners have too few neighbours: spheres of k_n r, not grown.
    if (std::abs(longest - shortest) < 1e-6f &&
        std::abs(longest - parameters.anisotropy_isotropic_scale * kRadius) < 1e-6f)
      continue;
    EXPECT_GE(shortest, kRadius * 0.9999f);
    EXPECT_LE(longest, largest * kRadius * 1.0001f);
    grownPastYuAndTurk += longest > parameters.max_ellipsoid_scale * kRadius * 1.0001f;
  }
  EXPECT_GT(grownPastYuAndTurk, 0u);
  EXPECT_EQ(reached.isotropicInterior, yuAndTurk.isotropicInterior);
}

}  // namespace
}  // namespace spindrift
