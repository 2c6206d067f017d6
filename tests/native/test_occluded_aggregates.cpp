// Leaving out of each depth layer the aggregates that the view hides (prep/OccludedAggregates.cpp): through
// the centre of every pixel of the view, the front layer's ellipsoids must give the same nearest entry as all
// of them and the back layer's the same farthest exit (a double-precision CPU ray cast); a lattice of
// separate spheres, which the interior test cannot thin, must lose most of its particles, also from a view
// as distant as a sun's; and nothing may go where the near plane cuts the body. The frame-level checks (every
// layer bit-identical, with a domain box, solids and a sun) are in test_hidden_interior.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "EllipsoidRayCast.h"
#include "LiquidTestScenes.h"
#include "prep/HiddenInterior.h"
#include "prep/LiquidPreparation.h"
#include "prep/OccludedAggregates.h"
#include "prep/SolidDepthTiles.h"
#include "spindrift/FloatImage.h"

namespace spindrift {
namespace {

using ellipsoid_test::nearestEntryAndFarthestExit;
using ellipsoid_test::shownAtPixel;

// The ray through a pixel's centre (x right, y down), in double precision: a point a metre before the eye in
// float world coordinates would be off by a float's rounding of the eye's position, 300 m away too much.
glm::dvec3 pixelRay(const Camera& camera, int x, int y) {
  const double focal = 0.5 * camera.height / std::tan(0.5 * double(glm::radians(camera.fovYDegrees)));
  const glm::dvec3 inCamera((x + 0.5 - 0.5 * camera.width) / focal, (0.5 * camera.height - (y + 0.5)) / focal,
                            -1.0);
  return glm::normalize(glm::dmat3(glm::mat3(camera.worldFromCamera)) * inCamera);
}

// The ray's distances where it enters and leaves a box (its frame rigid in the world's), as the impostor pass
// clips each ellipsoid's chord; a ray that misses it gets an empty range.
std::pair<double, double> boxChord(const DomainBox& box, const glm::dvec3& origin,
                                   const glm::dvec3& direction) {
  const glm::dmat4 boxFromWorld = glm::inverse(glm::dmat4(box.worldFromBox));
  const glm::dvec3 o(boxFromWorld * glm::dvec4(origin, 1.0)), d(glm::dmat3(boxFromWorld) * direction);
  double enter = -1e300, leave = 1e300;
  for (int axis = 0; axis < 3; ++axis) {
    const double a = (box.low[axis] - o[axis]) / d[axis], b = (box.high[axis] - o[axis]) / d[axis];
    enter = std::max(enter, std::min(a, b));
    leave = std::min(leave, std::max(a, b));
  }
  return {enter, leave};
}

// Nearest entry and farthest exit over the ellipsoids' chords clipped to the box (1e10 and -1e10 where none
// is left).
std::pair<double, double> clippedEntryAndExit(const std::vector<EllipsoidInstance>& ellipsoids,
                                              const glm::dvec3& origin, const glm::dvec3& direction,
                                              const std::pair<double, double>& box) {
  double nearest = 1e10, farthest = -1e10;
  for (const EllipsoidInstance& ellipsoid : ellipsoids) {
    const ellipsoid_test::Chord chord = ellipsoid_test::castRay(ellipsoid, origin, direction);
    const double entry = std::max(chord.entry, box.first), exit = std::min(chord.exit, box.second);
    if (chord.miss < 0.0 || !(entry < exit)) continue;
    nearest = std::min(nearest, entry);
    farthest = std::max(farthest, exit);
  }
  return {nearest, farthest};
}

// Nearest entry and farthest exit over the ellipsoids whose entry lies before `solid` (a planar eye depth;
// `cosine` turns the ray's distances into planar depths), as the impostor pass draws them: a fragment whose
// entry lies at or behind the background's depth is discarded in both layers.
std::pair<double, double> entryAndExitBeforeSolid(const std::vector<EllipsoidInstance>& ellipsoids,
                                                  const glm::dvec3& origin, const glm::dvec3& direction,
                                                  double cosine, double solid) {
  double nearest = 1e10, farthest = -1e10;
  for (const EllipsoidInstance& ellipsoid : ellipsoids) {
    const ellipsoid_test::Chord chord = ellipsoid_test::castRay(ellipsoid, origin, direction);
    if (chord.miss < 0.0 || !(chord.entry * cosine < solid)) continue;
    nearest = std::min(nearest, chord.entry);
    farthest = std::max(farthest, chord.exit);
  }
  return {nearest, farthest};
}

struct PixelCheck {
  std::size_t hits = 0;
  std::size_t differing = 0;
};

// Through every pixel centre of the camera: the layers' lists against all ellipsoids, clipped to `box` when
// there is one.
PixelCheck everyPixel(const std::vector<EllipsoidInstance>& all, const std::vector<EllipsoidInstance>& kept,
                      const LayerSplit& split, const Camera& camera, const DomainBox* box = nullptr) {
  const std::vector<EllipsoidInstance> front(kept.begin(), kept.end() - std::ptrdiff_t(split.backOnly));
  const std::vector<EllipsoidInstance> back(kept.begin() + std::ptrdiff_t(split.frontOnly), kept.end());
  const glm::dvec3 eye(camera.position());
  PixelCheck check;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const glm::dvec3 direction = pixelRay(camera, x, y);
      const auto layers = [&](const std::vector<EllipsoidInstance>& list) {
        return box ? clippedEntryAndExit(list, eye, direction, boxChord(*box, eye, direction))
                   : nearestEntryAndFarthestExit(list, eye, direction);
      };
      const auto [allFront, allBack] = layers(all);
      if (allFront > 1e9) continue;
      ++check.hits;
      // Each layer as the impostor pass draws it there: the ellipsoids whose shown rectangle holds the pixel.
      const int windowY = camera.height - 1 - y;
      check.differing += layers(shownAtPixel(front, false, x, windowY)).first != allFront;
      check.differing += layers(shownAtPixel(back, true, x, windowY)).second != allBack;
    }
  return check;
}

// Through every pixel centre: the layers' lists against all ellipsoids, with a solid at a planar depth per
// pixel (top row first).
PixelCheck everyPixelBeforeSolids(const std::vector<EllipsoidInstance>& all,
                                  const std::vector<EllipsoidInstance>& kept, const LayerSplit& split,
                                  const Camera& camera, const std::vector<float>& solids) {
  const std::vector<EllipsoidInstance> front(kept.begin(), kept.end() - std::ptrdiff_t(split.backOnly));
  const std::vector<EllipsoidInstance> back(kept.begin() + std::ptrdiff_t(split.frontOnly), kept.end());
  const glm::dvec3 eye(camera.position());
  const glm::dvec3 forward = -glm::dvec3(glm::mat3(camera.worldFromCamera)[2]);
  PixelCheck check;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const glm::dvec3 direction = pixelRay(camera, x, y);
      const double cosine = glm::dot(direction, forward);
      const double solid = solids[std::size_t(y) * camera.width + x];
      const auto [allFront, allBack] = entryAndExitBeforeSolid(all, eye, direction, cosine, solid);
      if (allFront > 1e9) continue;
      ++check.hits;
      const int windowY = camera.height - 1 - y;
      check.differing +=
          entryAndExitBeforeSolid(shownAtPixel(front, false, x, windowY), eye, direction, cosine, solid)
              .first != allFront;
      check.differing +=
          entryAndExitBeforeSolid(shownAtPixel(back, true, x, windowY), eye, direction, cosine, solid)
              .second != allBack;
    }
  return check;
}

// A jittered block of spacing 0.1 from (0.05, 0.05, 0.05) to `high`, grown as a default Mantaflow domain
// grows its particles.
std::vector<EllipsoidInstance> jitteredGrownBlock(const glm::vec3& high, unsigned seed,
                                                  const Camera& camera) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> jitter(-0.03f, 0.03f);
  std::vector<glm::vec3> positions = liquid_test::block({0.05f, 0.05f, 0.05f}, high, 0.1f);
  for (glm::vec3& position : positions)
    position += glm::vec3(jitter(random), jitter(random), jitter(random));
  LiquidParameters parameters;
  parameters.surface_offset = 1.9f;
  return prepareLiquid(liquid_test::particlesOf(positions, 0.11f), camera, parameters).aggregates;
}

// A jittered 16 x 16 x 10 block.
std::vector<EllipsoidInstance> jitteredBlock(const Camera& camera) {
  return jitteredGrownBlock({1.55f, 1.55f, 0.95f}, 3, camera);
}

// Spheres of radius 0.048 on a lattice of spacing 0.1: none touches another.
std::vector<EllipsoidInstance> separateSpheres() {
  std::vector<EllipsoidInstance> spheres;
  for (const glm::vec3& centre : liquid_test::block({0.05f, 0.05f, 0.05f}, {0.95f, 0.95f, 0.95f}, 0.1f)) {
    EllipsoidInstance sphere{};
    sphere.centreAndBoundingRadius = glm::vec4(centre, 0.048f);
    for (int axis = 0; axis < 3; ++axis) {
      sphere.inverseAxesRows[axis] = glm::vec4(0.0f);
      sphere.inverseAxesRows[axis][axis] = 1.0f / 0.048f;
    }
    spheres.push_back(sphere);
  }
  return spheres;
}

TEST(OccludedAggregates, EveryPixelSeesInEachLayerWhatAllEllipsoidsGive) {
  const Camera camera = Camera::lookAt(128, 96, 40.0f, {4.0f, -2.5f, 3.0f}, {0.8f, 0.8f, 0.4f}, {0, 0, 1});
  const std::vector<EllipsoidInstance> all = jitteredBlock(camera);
  std::vector<EllipsoidInstance> kept = all;
  LayerSplit split;
  const OccludedAggregatesResult result = dropOccludedAggregates(kept, split, camera, nullptr, nullptr);
  EXPECT_EQ(result.dropped + kept.size(), all.size());
  // The near side hides the far side's fronts and the other way round: most go from each layer.
  EXPECT_GT(result.hiddenFromFront, all.size() / 2) << "of " << all.size();
  EXPECT_GT(result.hiddenFromBack, all.size() / 2) << "of " << all.size();
  EXPECT_GT(result.dropped, all.size() / 4) << "of " << all.size();
  // The kept ones are drawn over a small part of their rectangles: where they may hold a layer's surface.
  EXPECT_GT(result.shownPixels, 0u);
  EXPECT_LT(result.shownPixels, result.reachPixels / 4) << "of " << result.reachPixels;
  const PixelCheck check = everyPixel(all, kept, split, camera);
  EXPECT_GT(check.hits, 2500u);  // 3,000 or so: the block fills much of the view
  EXPECT_EQ(check.differing, 0u) << "of " << 2 * check.hits << " layer values";
}

// A workspace lent from call to call (a sequence's frames) changes nothing: each call, whether the
// workspace's memory is fresh, reused with room to spare or grown, leaves what a call with none leaves, for
// block sizes that shrink and grow. Its memory grows only.
TEST(OccludedAggregates, AWorkspaceReusedAcrossCallsGivesWhatAFreshCallGives) {
  const Camera camera = Camera::lookAt(128, 96, 40.0f, {4.0f, -2.5f, 3.0f}, {0.8f, 0.8f, 0.4f}, {0, 0, 1});
  const std::vector<EllipsoidInstance> block = jitteredBlock(camera);
  OcclusionWorkspace workspace;
  std::size_t largest = 0;
  for (const std::size_t count : {block.size() / 2, block.size(), block.size() / 3, block.size()}) {
    std::vector<EllipsoidInstance> fresh(block.begin(), block.begin() + std::ptrdiff_t(count)),
        reused = fresh;
    LayerSplit freshSplit, reusedSplit;
    const OccludedAggregatesResult alone =
        dropOccludedAggregates(fresh, freshSplit, camera, nullptr, nullptr);
    const OccludedAggregatesResult lent =
        dropOccludedAggregates(reused, reusedSplit, camera, nullptr, nullptr, &workspace);
    largest = std::max(largest, count);
    EXPECT_EQ(workspace.capacity(), largest);
    EXPECT_GT(alone.dropped, 0u) << count;
    EXPECT_EQ(alone.dropped, lent.dropped) << count;
    EXPECT_EQ(alone.shownPixels, lent.shownPixels) << count;
    EXPECT_EQ(freshSplit.frontOnly, reusedSplit.frontOnly) << count;
    EXPECT_EQ(freshSplit.backOnly, reusedSplit.backOnly) << count;
    ASSERT_EQ(fresh.size(), reused.size()) << count;
    EXPECT_EQ(std::memcmp(fresh.data(), reused.data(), fresh.size() * sizeof(EllipsoidInstance)), 0) << count;
  }
}

TEST(OccludedAggregates, WhatTheSolidsHideAtEveryPixelGoesFromBothLayers) {
  // The background's depth holds a wall before the block's left part and a floor-like slope behind its
  // right part; every layer must still give, through every pixel, what all the ellipsoids the impostor pass
  // keeps there give (those whose entry lies before the solid).
  const Camera camera = Camera::lookAt(128, 96, 40.0f, {4.0f, -2.5f, 3.0f}, {0.8f, 0.8f, 0.4f}, {0, 0, 1});
  const std::vector<EllipsoidInstance> all = jitteredBlock(camera);
  FloatImage depth{camera.width, camera.height, 1, {}};
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x)
      depth.pixels.push_back(x < 64 ? 3.7f : x > 96 ? 4.2f + 0.01f * float(y) : INFINITY);
  SolidDepthTiles solids(camera);
  solids.addDepthImage(depth);

  std::vector<EllipsoidInstance> open = all, walled = all;
  LayerSplit openSplit, walledSplit;
  const OccludedAggregatesResult withoutSolids =
      dropOccludedAggregates(open, openSplit, camera, nullptr, nullptr);
  const OccludedAggregatesResult withSolids =
      dropOccludedAggregates(walled, walledSplit, camera, nullptr, &solids);
  // Every ellipsoid whose entry lies a margin behind the solid at every pixel its ray meets it goes, though
  // the solids keep the view from hiding much else (a covering ellipsoid counts for the back layer only where
  // no solid may lie before it).
  const glm::dvec3 eye(camera.position());
  const glm::dvec3 forward = -glm::dvec3(glm::mat3(camera.worldFromCamera)[2]);
  std::size_t whollyHidden = 0, keptThough = 0;
  for (const EllipsoidInstance& ellipsoid : all) {
    bool seen = false, hidden = true;
    for (int y = 0; y < camera.height && hidden; ++y)
      for (int x = 0; x < camera.width && hidden; ++x) {
        const glm::dvec3 direction = pixelRay(camera, x, y);
        const ellipsoid_test::Chord chord = ellipsoid_test::castRay(ellipsoid, eye, direction);
        if (chord.miss < 0.0) continue;
        seen = true;
        hidden = chord.entry * glm::dot(direction, forward) >
                 depth.pixels[std::size_t(y) * camera.width + x] + 0.05;
      }
    if (!seen || !hidden) continue;
    ++whollyHidden;
    keptThough += std::any_of(walled.begin(), walled.end(), [&](const EllipsoidInstance& kept) {
      return ellipsoid_test::sameShape(kept, ellipsoid);
    });
  }
  EXPECT_GT(whollyHidden, 500u) << "of " << all.size();
  EXPECT_EQ(keptThough, 0u) << "of " << whollyHidden;
  EXPECT_GT(withoutSolids.dropped, 0u);
  const PixelCheck check = everyPixelBeforeSolids(all, walled, walledSplit, camera, depth.pixels);
  EXPECT_GT(check.hits, 1000u);
  EXPECT_EQ(check.differing, 0u) << "of " << 2 * check.hits << " layer values";
}

TEST(OccludedAggregates, SeparateSpheresAreThinnedWhereTheInteriorTestCannot) {
  // From an oblique close camera and from as far as a sun's view (300 sizes away, where the angles a sphere
  // is seen under are below a float's resolution of their cosines).
  for (const float distance : {4.0f, 300.0f}) {
    const glm::vec3 direction = glm::normalize(glm::vec3(0.4f, -0.6f, 1.0f));
    const Camera camera = Camera::lookAt(160, 160, glm::degrees(2.0f * std::atan(1.0f / distance)),
                                         glm::vec3(0.5f) + distance * direction, glm::vec3(0.5f), {0, 0, 1});
    const std::vector<EllipsoidInstance> all = separateSpheres();
    std::vector<EllipsoidInstance> interior = all;
    EXPECT_EQ(dropHiddenInterior(interior, camera, nullptr).dropped, 0u) << "at " << distance;
    std::vector<EllipsoidInstance> kept = all;
    LayerSplit split;
    const OccludedAggregatesResult result = dropOccludedAggregates(kept, split, camera, nullptr, nullptr);
    EXPECT_GT(result.dropped, all.size() / 3) << "of " << all.size() << " at " << distance;
    EXPECT_GT(result.hiddenFromFront, all.size() / 2) << "of " << all.size() << " at " << distance;
    EXPECT_GT(result.hiddenFromBack, all.size() / 2) << "of " << all.size() << " at " << distance;
    const PixelCheck check = everyPixel(all, kept, split, camera);
    EXPECT_GT(check.hits, 5000u) << "at " << distance;
    EXPECT_EQ(check.differing, 0u) << "of " << 2 * check.hits << " layer values at " << distance;
  }
}

TEST(OccludedAggregates, EllipsoidsTheDomainBoxCutsCoverWhatTheBoxLeavesOfThem) {
  // A sheet of water three particles deep on a domain's floor, the box turned about z and one of its walls
  // through the sheet: every grown ellipsoid reaches the floor, as on the dam-break example, where the box
  // cut 30,270 of the 37,070 ellipsoids of the front layer. Seen from above, from the side (through the
  // wall's cut) and from below the floor, each layer still sees through every pixel what all ellipsoids,
  // clipped to the box, give, and most of the sheet goes from each layer.
  DomainBox box;
  box.worldFromBox = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.8f, 0.8f, 0.0f)),
                                 glm::radians(30.0f), glm::vec3(0.0f, 0.0f, 1.0f));
  box.low = glm::vec3(-3.0f, -3.0f, 0.04f);
  box.high = glm::vec3(3.0f, 0.5f, 3.0f);
  const Camera cameras[] = {
      Camera::lookAt(128, 96, 40.0f, {3.0f, -2.0f, 2.5f}, {0.8f, 0.8f, 0.1f}, {0, 0, 1}),
      Camera::lookAt(128, 96, 40.0f, {0.8f - 2.0f, 0.8f + 3.5f, 0.4f}, {0.8f, 0.8f, 0.1f}, {0, 0, 1}),
      Camera::lookAt(128, 96, 40.0f, {1.5f, 0.2f, -2.5f}, {0.8f, 0.8f, 0.1f}, {0, 0, 1})};
  for (const Camera& camera : cameras) {
    const std::vector<EllipsoidInstance> all = jitteredGrownBlock({1.55f, 1.55f, 0.25f}, 5, camera);
    std::size_t cut = 0;
    for (const EllipsoidInstance& ellipsoid : all)
      cut += ellipsoid.centreAndBoundingRadius.z - ellipsoid.centreAndBoundingRadius.w < box.low.z;
    EXPECT_EQ(cut, all.size());
    std::vector<EllipsoidInstance> kept = all;
    LayerSplit split;
    const OccludedAggregatesResult result = dropOccludedAggregates(kept, split, camera, &box, nullptr);
    EXPECT_GT(result.hiddenFromFront, all.size() / 3) << "of " << all.size();
    EXPECT_GT(result.hiddenFromBack, all.size() / 3) << "of " << all.size();
    const PixelCheck check = everyPixel(all, kept, split, camera, &box);
    EXPECT_GT(check.hits, 1000u);
    EXPECT_EQ(check.differing, 0u) << "of " << 2 * check.hits << " layer values";
  }
}

TEST(OccludedAggregates, KeepsTheSplitOfTheInteriorTestAndRefinesIt) {
  // After the interior test, [front only | both | back only] stays in that order and each layer still sees
  // through every pixel what all ellipsoids give.
  const Camera camera = Camera::lookAt(128, 128, 40.0f, {0.8f, 0.8f, 6.0f}, {0.8f, 0.8f, 0.5f}, {0, 1, 0});
  const std::vector<EllipsoidInstance> all = jitteredBlock(camera);
  std::vector<EllipsoidInstance> kept = all;
  HiddenInteriorResult interior = dropHiddenInterior(kept, camera, nullptr);
  ASSERT_GT(interior.split.frontOnly + interior.split.backOnly, 0u);
  const OccludedAggregatesResult result =
      dropOccludedAggregates(kept, interior.split, camera, nullptr, nullptr);
  EXPECT_GT(result.dropped, 0u);
  EXPECT_EQ(interior.dropped + result.dropped + kept.size(), all.size());
  const PixelCheck check = everyPixel(all, kept, interior.split, camera);
  EXPECT_GT(check.hits, 4000u);
  EXPECT_EQ(check.differing, 0u) << "of " << 2 * check.hits << " layer values";
}

TEST(OccludedAggregates, WhatReachesTheNearPlaneIsKeptInBothLayers) {
  // The camera inside the block: the ellipsoids around the eye reach the near plane, where the impostor pass
  // clips them, so they neither cover nor go.
  Camera camera = Camera::lookAt(96, 64, 60.0f, {0.8f, 0.8f, 0.5f}, {1.5f, 0.8f, 0.5f}, {0, 0, 1});
  camera.nearClip = 0.05f;
  const std::vector<EllipsoidInstance> all = jitteredBlock(camera);
  std::vector<EllipsoidInstance> kept = all;
  LayerSplit split;
  const OccludedAggregatesResult result = dropOccludedAggregates(kept, split, camera, nullptr, nullptr);
  EXPECT_GT(result.dropped, 0u) << "the walls far from the eye still hide what lies behind them";
  const std::vector<EllipsoidInstance> front(kept.begin(), kept.end() - std::ptrdiff_t(split.backOnly));
  const std::vector<EllipsoidInstance> back(kept.begin() + std::ptrdiff_t(split.frontOnly), kept.end());
  const auto holds = [](const std::vector<EllipsoidInstance>& list, const EllipsoidInstance& ellipsoid) {
    for (const EllipsoidInstance& other : list)
      if (ellipsoid_test::sameShape(other, ellipsoid)) return true;
    return false;
  };
  const glm::mat4 cameraFromWorld = camera.cameraFromWorld();
  std::size_t reaching = 0;
  for (const EllipsoidInstance& ellipsoid : all) {
    const glm::vec4& sphere = ellipsoid.centreAndBoundingRadius;
    const float depth = -(cameraFromWorld * glm::vec4(glm::vec3(sphere), 1.0f)).z;
    if (depth - sphere.w > camera.nearClip) continue;
    ++reaching;
    EXPECT_TRUE(holds(front, ellipsoid) && holds(back, ellipsoid));
  }
  EXPECT_GT(reaching, 0u);
}

TEST(OccludedAggregates, EmptyAndDegenerateInputsAreLeftAlone) {
  const Camera camera = Camera::lookAt(64, 64, 40.0f, {0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  std::vector<EllipsoidInstance> none;
  LayerSplit split;
  EXPECT_EQ(dropOccludedAggregates(none, split, camera, nullptr, nullptr).dropped, 0u);
  // Identical spheres: each one's cover is its own depth range, so none hides another.
  std::vector<EllipsoidInstance> same(10, separateSpheres().front());
  EXPECT_EQ(dropOccludedAggregates(same, split, camera, nullptr, nullptr).dropped, 0u);
  EXPECT_EQ(same.size(), 10u);
  // A sphere just beyond the near plane, a million pixels to the side: it reaches no pixel, so it draws
  // nothing and goes, without overflowing a pixel coordinate.
  Camera near = camera;
  near.nearClip = 1e-3f;
  std::vector<EllipsoidInstance> aside(1, separateSpheres().front());
  aside[0].centreAndBoundingRadius = glm::vec4(5000.0f, 0.0f, 5.0f - 0.002f - 0.048f, 0.048f);
  LayerSplit asideSplit;
  EXPECT_EQ(dropOccludedAggregates(aside, asideSplit, near, nullptr, nullptr).dropped, 1u);
  // A zero-size camera and a NaN particle: nothing happens, nothing crashes.
  Camera empty = camera;
  empty.width = 0;
  EXPECT_EQ(dropOccludedAggregates(same, split, empty, nullptr, nullptr).dropped, 0u);
  std::vector<EllipsoidInstance> broken = separateSpheres();
  broken[5].centreAndBoundingRadius.x = std::nanf("");
  const std::size_t before = broken.size();
  dropOccludedAggregates(broken, split, camera, nullptr, nullptr);
  EXPECT_LE(broken.size(), before);
  bool nanKept = false;
  for (const EllipsoidInstance& ellipsoid : broken)
    nanKept |= std::isnan(ellipsoid.centreAndBoundingRadius.x);
  EXPECT_TRUE(nanKept) << "an ellipsoid the test cannot place is left to the impostor pass";
}

}  // namespace
}  // namespace spindrift
