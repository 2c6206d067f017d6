// Leaving out the aggregates hidden inside the body (prep/HiddenInterior.cpp, liquid.drop_hidden_interior):
// every ellipsoid left out must lie inside the union of those kept, checked by a brute-force CPU test of
// points on its surface against every kept ellipsoid; each depth layer's own list must give what all
// ellipsoids give (a CPU ray cast from the camera); the frame's layers must be bit-identical with and
// without it; and nothing may be left out where a clip plane or the domain's walls cut the body.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "EllipsoidRayCast.h"
#include "LiquidTestScenes.h"
#include "prep/Anisotropy.h"
#include "prep/HiddenInterior.h"
#include "prep/LayerOrder.h"
#include "prep/LiquidPreparation.h"
#include "spindrift/FrameInputs.h"
#include "spindrift/Scene.h"

namespace spindrift {
namespace {

constexpr float kSpacing = 0.1f;
constexpr float kRadius = 0.11f;

// A lattice block between `low` and `high`, each particle moved by up to 0.3 spacings (as FLIP particles
// sit), seeded.
Particles jitteredBlock(const glm::vec3& low, const glm::vec3& high, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> jitter(-0.3f * kSpacing, 0.3f * kSpacing);
  std::vector<glm::vec3> positions = liquid_test::block(low, high, kSpacing);
  for (glm::vec3& position : positions)
    position += glm::vec3(jitter(random), jitter(random), jitter(random));
  return liquid_test::particlesOf(positions, kRadius);
}

// 16 x 16 x 10 particles.
Particles jitteredBlock() {
  return jitteredBlock({0.05f, 0.05f, 0.05f}, {1.55f, 1.55f, 0.95f}, 7);
}

Camera obliqueCamera() {
  return Camera::lookAt(128, 96, 40.0f, {4.0f, -2.5f, 3.0f}, {0.8f, 0.8f, 0.4f}, {0, 0, 1});
}

LiquidParameters grownParticles() {
  LiquidParameters parameters;
  parameters.surface_offset = 1.9f;  // what a default Mantaflow domain derives (docs/mantaflow-caches.md)
  return parameters;
}

float ellipsoidValue(const EllipsoidInstance& ellipsoid, const glm::dvec3& point) {
  const glm::dvec3 offset = point - glm::dvec3(ellipsoid.centreAndBoundingRadius);
  const glm::dvec3 scaled(glm::dot(glm::dvec3(ellipsoid.inverseAxesRows[0]), offset),
                          glm::dot(glm::dvec3(ellipsoid.inverseAxesRows[1]), offset),
                          glm::dot(glm::dvec3(ellipsoid.inverseAxesRows[2]), offset));
  return float(glm::length(scaled));
}

// Points on an ellipsoid's surface: a Fibonacci lattice of unit directions mapped through its axes.
std::vector<glm::dvec3> surfacePoints(const EllipsoidInstance& ellipsoid, int count) {
  const glm::dmat3 inverseAxes = glm::transpose(glm::dmat3(glm::dvec3(ellipsoid.inverseAxesRows[0]),
                                                           glm::dvec3(ellipsoid.inverseAxesRows[1]),
                                                           glm::dvec3(ellipsoid.inverseAxesRows[2])));
  const glm::dmat3 axes = glm::inverse(inverseAxes);
  std::vector<glm::dvec3> points;
  const double golden = 3.14159265358979 * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < count; ++k) {
    const double z = 1.0 - 2.0 * (k + 0.5) / count, ring = std::sqrt(1.0 - z * z);
    const glm::dvec3 direction(ring * std::cos(golden * k), ring * std::sin(golden * k), z);
    points.push_back(glm::dvec3(ellipsoid.centreAndBoundingRadius) + axes * direction);
  }
  return points;
}

using ellipsoid_test::nearestEntryAndFarthestExit;

bool contains(const std::vector<EllipsoidInstance>& ellipsoids, const EllipsoidInstance& ellipsoid) {
  for (const EllipsoidInstance& other : ellipsoids)
    if (ellipsoid_test::sameShape(other, ellipsoid)) return true;
  return false;
}

// The ellipsoids of `all` that are not in `kept` (kept is reordered by layer).
std::vector<EllipsoidInstance> leftOut(const std::vector<EllipsoidInstance>& all,
                                       const std::vector<EllipsoidInstance>& kept) {
  std::vector<EllipsoidInstance> dropped;
  for (const EllipsoidInstance& ellipsoid : all)
    if (!contains(kept, ellipsoid)) dropped.push_back(ellipsoid);
  return dropped;
}

// The front layer's ellipsoids (all but the trailing back-only ones) and the back layer's.
std::vector<EllipsoidInstance> frontLayer(const std::vector<EllipsoidInstance>& kept,
                                          const LayerSplit& split) {
  return {kept.begin(), kept.end() - std::ptrdiff_t(split.backOnly)};
}
std::vector<EllipsoidInstance> backLayer(const std::vector<EllipsoidInstance>& kept,
                                         const LayerSplit& split) {
  return {kept.begin() + std::ptrdiff_t(split.frontOnly), kept.end()};
}

TEST(HiddenInterior, EveryEllipsoidLeftOutLiesInsideTheOthers) {
  const Camera camera = obliqueCamera();
  const LiquidPreparation preparation = prepareLiquid(jitteredBlock(), camera, grownParticles());
  const std::vector<EllipsoidInstance>& all = preparation.aggregates;
  std::vector<EllipsoidInstance> kept = all;
  const HiddenInteriorResult result = dropHiddenInterior(kept, camera, nullptr);
  EXPECT_EQ(result.notApplied, "");
  EXPECT_EQ(result.dropped + kept.size(), all.size());
  // The block is 10 particles (9 radii) thick; the kept shell is about two radii deep on each side.
  EXPECT_GT(result.dropped, all.size() / 5) << "of " << all.size();
  const std::vector<EllipsoidInstance> dropped = leftOut(all, kept);
  ASSERT_EQ(dropped.size(), result.dropped);

  // No point of a dropped ellipsoid is on the union's boundary: each lies strictly inside another ellipsoid.
  std::size_t onBoundary = 0, checked = 0;
  for (std::size_t d = 0; d < dropped.size(); d += 3)
    for (const glm::dvec3& point : surfacePoints(dropped[d], 96)) {
      ++checked;
      bool inside = false;
      for (const EllipsoidInstance& other : all)
        if (!ellipsoid_test::sameShape(other, dropped[d]) && ellipsoidValue(other, point) < 1.0f) {
          inside = true;
          break;
        }
      onBoundary += !inside;
    }
  EXPECT_GT(checked, 10000u);
  EXPECT_EQ(onBoundary, 0u) << "of " << checked << " surface points of dropped ellipsoids";
}

TEST(HiddenInterior, RaysFromAnySideMeetTheSameFrontAndBack) {
  // The layers are nearest entry and farthest exit; from outside the body they must not change, whichever
  // side the rays come from (the same ellipsoids serve the lights' views).
  const Camera camera = obliqueCamera();
  const std::vector<EllipsoidInstance> all =
      prepareLiquid(jitteredBlock(), camera, grownParticles()).aggregates;
  std::vector<EllipsoidInstance> kept = all;
  ASSERT_GT(dropHiddenInterior(kept, camera, nullptr).dropped, 0u);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::size_t hits = 0, differing = 0;
  for (int ray = 0; ray < 3000; ++ray) {
    glm::dvec3 direction(unit(random), unit(random), unit(random));
    if (glm::length(direction) < 0.1) continue;
    direction = glm::normalize(direction);
    const glm::dvec3 target(0.8 + 0.7 * unit(random), 0.8 + 0.7 * unit(random), 0.5 + 0.4 * unit(random));
    const glm::dvec3 origin = target - 5.0 * direction;
    const auto [allFront, allBack] = nearestEntryAndFarthestExit(all, origin, direction);
    const auto [keptFront, keptBack] = nearestEntryAndFarthestExit(kept, origin, direction);
    if (allFront > 1e9) continue;
    ++hits;
    differing += allFront != keptFront || allBack != keptBack;
  }
  EXPECT_GT(hits, 2000u);
  EXPECT_EQ(differing, 0u) << "of " << hits << " rays";
}

// Rays from the camera's eye towards random points of a box: the front layer's ellipsoids give every ray's
// nearest entry, the back layer's its farthest exit, exactly as all of them do.
void expectLayersSeeWhatAllGive(const std::vector<EllipsoidInstance>& all,
                                const std::vector<EllipsoidInstance>& kept, const LayerSplit& split,
                                const Camera& camera, const glm::dvec3& low, const glm::dvec3& high) {
  ASSERT_LE(split.frontOnly + split.backOnly, kept.size());
  const std::vector<EllipsoidInstance> front = frontLayer(kept, split);
  const std::vector<EllipsoidInstance> back = backLayer(kept, split);
  const glm::dvec3 eye(camera.position());
  std::mt19937 random(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t hits = 0, differing = 0;
  for (int ray = 0; ray < 4000; ++ray) {
    const glm::dvec3 target = low + (high - low) * glm::dvec3(unit(random), unit(random), unit(random));
    const glm::dvec3 direction = glm::normalize(target - eye);
    const auto [allFront, allBack] = nearestEntryAndFarthestExit(all, eye, direction);
    if (allFront > 1e9) continue;
    ++hits;
    differing += nearestEntryAndFarthestExit(front, eye, direction).first != allFront;
    differing += nearestEntryAndFarthestExit(back, eye, direction).second != allBack;
  }
  EXPECT_GT(hits, 2500u);
  EXPECT_EQ(differing, 0u) << "of " << 2 * hits << " layer values";
}

TEST(HiddenInterior, EachLayerSeesFromTheCameraWhatAllEllipsoidsGive) {
  const Camera camera = obliqueCamera();
  const std::vector<EllipsoidInstance> all =
      prepareLiquid(jitteredBlock(), camera, grownParticles()).aggregates;
  std::vector<EllipsoidInstance> kept = all;
  const HiddenInteriorResult result = dropHiddenInterior(kept, camera, nullptr);
  EXPECT_GT(result.split.frontOnly, 0u);
  EXPECT_GT(result.split.backOnly, 0u);
  expectLayersSeeWhatAllGive(all, kept, result.split, camera, {0.0, 0.0, 0.0}, {1.6, 1.6, 1.0});
}

TEST(HiddenInterior, AFlatSlabSeenFromAboveDrawsItsTopIntoTheFrontLayerAndItsBottomIntoTheBack) {
  // 24 x 24 x 6 particles seen from straight above: the top face's particles are drawn into the front layer
  // only and the bottom face's into the back layer only; a split the wrong way round fails here.
  const Particles slab = jitteredBlock({0.05f, 0.05f, 0.05f}, {2.35f, 2.35f, 0.55f}, 5);
  const Camera above = Camera::lookAt(128, 128, 40.0f, {1.2f, 1.2f, 6.0f}, {1.2f, 1.2f, 0.3f}, {0, 1, 0});
  const std::vector<EllipsoidInstance> all = prepareLiquid(slab, above, grownParticles()).aggregates;
  std::vector<EllipsoidInstance> kept = all;
  const HiddenInteriorResult result = dropHiddenInterior(kept, above, nullptr);
  EXPECT_GT(result.split.frontOnly, kept.size() / 10) << "of " << kept.size();
  EXPECT_GT(result.split.backOnly, kept.size() / 10) << "of " << kept.size();
  const auto meanHeight = [&](std::size_t first, std::size_t count) {
    double sum = 0.0;
    for (std::size_t i = first; i < first + count; ++i)
      sum += kept[i].centreAndBoundingRadius.z;
    return count ? sum / double(count) : 0.0;
  };
  const double middle = 0.3;  // of the particles' heights, 0.05 to 0.55
  EXPECT_GT(meanHeight(0, result.split.frontOnly), middle + 0.1);
  EXPECT_LT(meanHeight(kept.size() - result.split.backOnly, result.split.backOnly), middle - 0.1);
  expectLayersSeeWhatAllGive(all, kept, result.split, above, {0.0, 0.0, 0.0}, {2.4, 2.4, 0.6});
}

TEST(HiddenInterior, NothingIsLeftOutWhenTheNearPlaneCutsTheBody) {
  // The camera inside the block: rays start inside the body, where a cavity would show.
  const Camera camera = Camera::lookAt(128, 96, 40.0f, {0.8f, 0.8f, 0.5f}, {1.5f, 0.8f, 0.5f}, {0, 0, 1});
  std::vector<EllipsoidInstance> ellipsoids =
      prepareLiquid(jitteredBlock(), camera, grownParticles()).aggregates;
  const std::size_t before = ellipsoids.size();
  ASSERT_GT(before, 256u);
  const HiddenInteriorResult result = dropHiddenInterior(ellipsoids, camera, nullptr);
  EXPECT_EQ(result.dropped, 0u);
  EXPECT_EQ(ellipsoids.size(), before);
  EXPECT_NE(result.notApplied, "");
}

TEST(HiddenInterior, EllipsoidsThatReachTheDomainWallsAreKept) {
  const Camera camera = obliqueCamera();
  const std::vector<EllipsoidInstance> all =
      prepareLiquid(jitteredBlock(), camera, grownParticles()).aggregates;
  // A floor under the block, the other walls far off: ellipsoids that reach below z = 0.05 are kept.
  const DomainBox box{glm::mat4(1.0f), glm::vec3(-1.0f, -1.0f, 0.05f), glm::vec3(3.0f)};
  std::vector<EllipsoidInstance> clipped = all, unclipped = all;
  const HiddenInteriorResult withBox = dropHiddenInterior(clipped, camera, &box);
  const HiddenInteriorResult withoutBox = dropHiddenInterior(unclipped, camera, nullptr);
  EXPECT_GT(withBox.dropped, 0u);
  EXPECT_LT(withBox.dropped, withoutBox.dropped);
  // The camera is above the floor, so rays leave the box through it: the floor cuts the back layer, and
  // every ellipsoid whose bounding sphere reaches it is still drawn there (its front may be hidden).
  const std::vector<EllipsoidInstance> back = backLayer(clipped, withBox.split);
  std::size_t atWalls = 0;
  for (const EllipsoidInstance& ellipsoid : all) {
    const glm::vec3 centre(ellipsoid.centreAndBoundingRadius);
    const float reach = ellipsoid.centreAndBoundingRadius.w;
    if (glm::all(glm::greaterThan(centre - reach, box.low)) &&
        glm::all(glm::lessThan(centre + reach, box.high)))
      continue;
    ++atWalls;
    EXPECT_TRUE(contains(back, ellipsoid));
  }
  EXPECT_GT(atWalls, 0u);
  EXPECT_GT(withBox.split.backOnly, 0u) << "fronts hidden although the floor cuts their backs";
}

TEST(HiddenInterior, ScatteredDropsAndSmallSetsAreLeftAlone) {
  const Camera camera = obliqueCamera();
  // Droplets 0.6 apart (six radii, more than their grown reach of 2.4 radii each) cover nothing of each
  // other.
  const Camera above = Camera::lookAt(128, 96, 40.0f, {5.7f, 5.7f, 40.0f}, {5.7f, 5.7f, 0.5f}, {0, 1, 0});
  std::vector<glm::vec3> positions;
  for (int i = 0; i < 400; ++i)
    positions.emplace_back(float(i % 20) * 0.6f, float(i / 20) * 0.6f, 0.5f);
  LiquidParameters parameters = grownParticles();
  parameters.layers = "merged";
  std::vector<EllipsoidInstance> scattered =
      prepareLiquid(liquid_test::particlesOf(positions, kRadius), above, parameters).aggregates;
  ASSERT_EQ(scattered.size(), 400u);
  EXPECT_EQ(dropHiddenInterior(scattered, above, nullptr).dropped, 0u);

  std::vector<EllipsoidInstance> none;
  EXPECT_EQ(dropHiddenInterior(none, camera, nullptr).dropped, 0u);
  std::vector<EllipsoidInstance> few(10, scattered.front());  // identical ones: each covers the others
  EXPECT_EQ(dropHiddenInterior(few, camera, nullptr).dropped, 0u);
  EXPECT_EQ(few.size(), 10u);
}

// Spheres of `radius` on a perfect cubic lattice of kSpacing, 12 on a side.
std::vector<EllipsoidInstance> latticeOfSpheres(float radius) {
  std::vector<EllipsoidInstance> spheres;
  for (const glm::vec3& position : liquid_test::block({0.05f, 0.05f, 0.05f}, {1.15f, 1.15f, 1.15f}, kSpacing))
    spheres.push_back(sphereInstance(position, radius));
  return spheres;
}

TEST(HiddenInterior, BallsTooSmallToCoverTheLatticeGapsAreNotTried) {
  const Camera camera = obliqueCamera();
  // Below the covering bound (sqrt(3) / 2 spacings, the cube centres' distance from the lattice points): the
  // test, run regardless, drops nothing, so skipping it loses nothing.
  std::vector<EllipsoidInstance> unchecked = latticeOfSpheres(0.85f * kSpacing);
  ASSERT_EQ(unchecked.size(), 1728u);
  EXPECT_EQ(dropHiddenInterior(unchecked, camera, nullptr).dropped, 0u);
  std::vector<EllipsoidInstance> checked = latticeOfSpheres(0.85f * kSpacing);
  const HiddenInteriorResult skipped = dropHiddenInterior(checked, camera, nullptr, nullptr, kSpacing);
  EXPECT_NE(skipped.notApplied.find("cannot cover"), std::string::npos) << skipped.notApplied;
  EXPECT_EQ(skipped.dropped, 0u);
  // Above it the balls close the gaps and the deep ones go.
  std::vector<EllipsoidInstance> overlapping = latticeOfSpheres(1.15f * kSpacing);
  const HiddenInteriorResult tried = dropHiddenInterior(overlapping, camera, nullptr, nullptr, kSpacing);
  EXPECT_EQ(tried.notApplied, "");
  EXPECT_GT(tried.dropped, 1728u / 4);
}

TEST(HiddenInterior, ParticleSpacingIsTheLatticesSpacing) {
  const LiquidPreparation preparation = prepareLiquid(jitteredBlock(), obliqueCamera(), grownParticles());
  EXPECT_NEAR(preparation.particleSpacing, kSpacing, 0.1f * kSpacing);
}

// The whole frame with and without: every channel of every layer bit-identical.
// `withDropped`, when given, receives the frame with them.
void expectIdenticalFrames(Scene scene, const Particles& particles,
                           const std::vector<TriangleMesh>& solids = {},
                           const std::optional<FloatImage>& backgroundDepth = std::nullopt,
                           RenderResult* withDropped = nullptr) {
  // In-memory particles with the scene's sources (a domain box) go through renderParticles; solids and a
  // background's depth need FrameInputs.
  FrameInputs inputs;
  inputs.particles = particles;
  inputs.occluders = solids;
  inputs.backgroundDepth = backgroundDepth;
  const auto render = [&] {
    return solids.empty() && !backgroundDepth ? liquid_test::renderer().renderParticles(scene, particles, 1)
                                              : liquid_test::renderer().renderFrame(scene, 1, inputs);
  };
  scene.parameters.liquid.drop_hidden_interior = false;
  const RenderResult all = render();
  scene.parameters.liquid.drop_hidden_interior = true;
  const RenderResult dropped = render();
  if (withDropped) *withDropped = dropped;
  liquid_test::expectAllChannelsFinite(dropped);
  // A solid before the body keeps the interior test from dropping a back half whose screen it may cover.
  if (!backgroundDepth) {
    EXPECT_GT(dropped.stats.liquid.hiddenInteriorDropped, 0u);
    EXPECT_GT(
        dropped.stats.liquid.hiddenInteriorFrontLayerOnly + dropped.stats.liquid.hiddenInteriorBackLayerOnly,
        0u);
  }
  EXPECT_EQ(all.stats.liquid.hiddenInteriorDropped, 0u);
  // The view hides more besides (prep/OccludedAggregates.cpp): the block's far side behind its near side.
  EXPECT_GT(dropped.stats.liquid.occludedDropped, 0u);
  EXPECT_EQ(all.stats.liquid.occludedDropped, 0u);
  if (!scene.lights.empty()) {
    EXPECT_GT(dropped.stats.light.viewParticlesLeftOut, 0u);
    // Without the interior tests a view leaves out only what light.column_particles thins (the sky's).
    EXPECT_EQ(all.stats.light.viewParticlesLeftOut, all.stats.light.viewParticlesColumnThinned);
  }
  ASSERT_EQ(all.layers.size(), dropped.layers.size());
  for (std::size_t l = 0; l < all.layers.size(); ++l) {
    ASSERT_EQ(all.layers[l].pixels.size(), dropped.layers[l].pixels.size());
    std::size_t differing = 0;
    for (std::size_t p = 0; p < all.layers[l].pixels.size(); ++p)
      differing += std::memcmp(&all.layers[l].pixels[p], &dropped.layers[l].pixels[p], sizeof(float)) != 0;
    EXPECT_EQ(differing, 0u) << all.layers[l].name;
  }
}

Scene blockScene() {
  Scene scene;
  scene.camera = obliqueCamera();
  scene.background.color = {0.4f, 0.5f, 0.6f};
  scene.parameters.liquid = grownParticles();
  return scene;
}

TEST(GLHiddenInterior, EveryLayerIsBitIdenticalWithAndWithout) {
  expectIdenticalFrames(blockScene(), jitteredBlock());
}

TEST(GLHiddenInterior, EveryLightPassIsBitIdenticalWithAndWithout) {
  // A sun at an angle: its view and the sky's drop what they hide, and the shadow, caustic and sky layers
  // stay the same to the bit.
  Scene scene = blockScene();
  Light sun;
  sun.type = Light::Type::Sun;
  sun.direction = glm::normalize(glm::vec3(0.3f, 0.5f, -0.8f));
  sun.strength = 3.0f;
  scene.lights.push_back(sun);
  scene.parameters.light.shadow_map_size = 128;
  expectIdenticalFrames(scene, jitteredBlock());
}

TEST(GLHiddenInterior, EveryLayerIsBitIdenticalInsideADomainBox) {
  Scene scene = blockScene();
  // The floor and one side wall cut the grown particles; the rest of the box is far.
  ParticleSource source;
  source.radius = kRadius;
  source.domainBox = DomainBox{glm::mat4(1.0f), glm::vec3(-1.0f, 0.1f, 0.05f), glm::vec3(3.0f, 3.0f, 3.0f)};
  scene.particles.push_back(source);
  expectIdenticalFrames(scene, jitteredBlock());
}

TEST(GLHiddenInterior, EveryLayerIsBitIdenticalWithASolidInsideTheBody) {
  // A plate submerged in the middle of the block: the passes hide particles whose front lies behind it, so
  // the back layer over the plate comes from particles deep inside the body, which must stay.
  TriangleMesh plate;
  plate.vertices = {{0.5f, 0.5f, 0.45f}, {1.1f, 0.5f, 0.45f}, {1.1f, 1.1f, 0.45f}, {0.5f, 1.1f, 0.45f}};
  plate.triangles = {{0, 1, 2}, {0, 2, 3}};
  expectIdenticalFrames(blockScene(), jitteredBlock(), {plate});
}

TEST(GLHiddenInterior, EveryLayerIsBitIdenticalBehindAWallInTheBackgroundsDepth) {
  // The background's depth holds a wall before the block's upper left, as a tank's wall hides a pool seen
  // from the side (its edge slanted, so that a picture flipped either way would hide other particles): the
  // passes hide every fragment whose entry lies behind it, so the particles there are left out: before they
  // are shaped where the wall hides their whole reach (prep/LiquidPreparation.cpp), else from both layers
  // where it hides them at every pixel (prep/OccludedAggregates.cpp). The frame stays the same to the bit: a
  // particle left out is still its neighbours' neighbour, and the density that sets the splashes apart is
  // the frame's (prep/FullNeighbourhood.h), not that of the particles a view shapes.
  const Scene scene = blockScene();
  const Camera& camera = scene.camera;
  const float nearestParticle = 4.0f;  // the block's nearest particles lie about 4.1 from the eye
  FloatImage wall{camera.width, camera.height, 1, {}};
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x)
      wall.pixels.push_back(x + y < (camera.width + camera.height) / 2 + 24
                                ? 0.8f * nearestParticle
                                : std::numeric_limits<float>::infinity());
  RenderResult walled;
  expectIdenticalFrames(scene, jitteredBlock(), {}, wall, &walled);
  // Every particle whose drawn ellipsoid lies wholly behind the wall goes: those whose centre lies 22 pixels
  // inside its edge (a grown particle reaches about 0.3 from its centre, 9 pixels here). Without the solids'
  // tests few do, as the solids keep the interior test and the other particles from hiding them.
  std::size_t behind = 0;
  for (const glm::vec3& position : jitteredBlock().positions) {
    const glm::vec3 pixel = camera.pixelAndDepthFromWorld(position);
    behind += pixel.x + pixel.y < 0.5f * float(camera.width + camera.height) + 24.0f - 22.0f;
  }
  EXPECT_GT(behind, 300u);
  const LiquidFrameStats& liquid = walled.stats.liquid;
  EXPECT_GE(liquid.hiddenBehindSolids + liquid.hiddenInteriorDropped + liquid.occludedDropped, behind);
  // Most are not even shaped: the solids hide their whole reach (prep/LiquidPreparation.cpp).
  EXPECT_GT(liquid.hiddenBehindSolids, behind / 2);
}

TEST(LayerOrder, KeepingTheBackLayerOnlyLeavesItsEllipsoidsInTheirOrder) {
  // Five ellipsoids told apart by their centres' x, [front only | both | back only] as 2, 2, 1.
  std::vector<EllipsoidInstance> ellipsoids(5);
  for (std::size_t i = 0; i < ellipsoids.size(); ++i)
    ellipsoids[i].centreAndBoundingRadius = glm::vec4(float(i), 0.0f, 0.0f, 1.0f);
  LayerSplit split{2, 1};
  EXPECT_EQ(keepBackLayerOnly(ellipsoids, split), 2u);
  ASSERT_EQ(ellipsoids.size(), 3u);
  for (std::size_t i = 0; i < ellipsoids.size(); ++i)
    EXPECT_EQ(ellipsoids[i].centreAndBoundingRadius.x, float(i + 2));
  EXPECT_EQ(split.frontOnly, 0u);
  EXPECT_EQ(split.backOnly, 3u);  // the front layer draws none of them

  // Degenerate: no ellipsoids; every one in the front layer only.
  std::vector<EllipsoidInstance> none;
  LayerSplit empty{0, 0};
  EXPECT_EQ(keepBackLayerOnly(none, empty), 0u);
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(empty.backOnly, 0u);
  std::vector<EllipsoidInstance> frontOnly(4);
  LayerSplit allFront{4, 0};
  EXPECT_EQ(keepBackLayerOnly(frontOnly, allFront), 4u);
  EXPECT_TRUE(frontOnly.empty());
}

}  // namespace
}  // namespace spindrift
