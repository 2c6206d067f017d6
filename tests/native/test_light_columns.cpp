// A light's view of a body few particles deep keeps, per texel column, the particles whose centres lie
// nearest (front layer) and farthest (back layer) (prep/LightColumns.h): checked against a brute-force
// selection over each column, computed here from the view's own projection.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "prep/LightColumns.h"

namespace spindrift {
namespace {

Camera lightView() {
  return Camera::lookAt(16, 16, 30.0f, {0.0f, 0.0f, 10.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f});
}

// Ellipsoids of radius 0.1 at `positions` (their centres are what is sorted).
std::vector<EllipsoidInstance> spheresAt(const std::vector<glm::vec3>& positions) {
  std::vector<EllipsoidInstance> spheres;
  for (const glm::vec3& position : positions) {
    EllipsoidInstance sphere{};
    sphere.centreAndBoundingRadius = glm::vec4(position, 0.1f);
    for (int k = 0; k < 3; ++k) {
      sphere.inverseAxesRows[k] = glm::vec4(0.0f);
      sphere.inverseAxesRows[k][k] = 10.0f;
    }
    spheres.push_back(sphere);
  }
  return spheres;
}

glm::vec3 centreOf(const EllipsoidInstance& ellipsoid) {
  return glm::vec3(ellipsoid.centreAndBoundingRadius);
}

// Which layers each position ends in: 'f' front only, 'b' both, 'k' back only, by the split's ranges.
std::map<std::vector<float>, char> layersOf(const std::vector<EllipsoidInstance>& kept,
                                            const LayerSplit& split) {
  std::map<std::vector<float>, char> layers;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    const glm::vec3 c = centreOf(kept[i]);
    layers[{c.x, c.y, c.z}] = i < split.frontOnly ? 'f' : (i >= kept.size() - split.backOnly ? 'k' : 'b');
  }
  return layers;
}

}  // namespace

TEST(LightColumns, EachLayerKeepsItsColumnsNearestAndFarthestCentres) {
  const Camera view = lightView();
  std::mt19937 random(7);
  std::uniform_real_distribution<float> across(-2.5f, 2.5f), deep(-1.0f, 1.0f);
  std::vector<glm::vec3> positions;
  for (int i = 0; i < 3000; ++i)
    positions.emplace_back(across(random), across(random), deep(random));
  // Columns of one texel, and of three, which do not divide the view's 16 (the last row and column are
  // narrower).
  for (const int side : {1, 3}) {
    SCOPED_TRACE("columns of " + std::to_string(side) + " texels");
    std::vector<EllipsoidInstance> ellipsoids = spheresAt(positions);
    LayerSplit split;
    const int perColumn = 2;
    const std::size_t leftOut = keepColumnEnds(ellipsoids, split, view, perColumn, side);

    // The brute-force selection: each position's column and depth, each column's two nearest and farthest.
    std::map<std::pair<int, int>, std::vector<std::pair<float, std::size_t>>> columns;
    std::vector<char> outside(positions.size(), 0);
    for (std::size_t i = 0; i < positions.size(); ++i) {
      const glm::vec3 pixel = view.pixelAndDepthFromWorld(positions[i]);
      if (pixel.x < 0.0f || pixel.y < 0.0f || pixel.x >= 16.0f || pixel.y >= 16.0f) {
        outside[i] = 1;
        continue;
      }
      columns[{int(pixel.x) / side, int(pixel.y) / side}].push_back({pixel.z, i});
    }
    std::map<std::vector<float>, char> expected;
    const auto mark = [&](std::size_t i, char layer) {
      const glm::vec3& p = positions[i];
      char& entry = expected[{p.x, p.y, p.z}];
      entry = entry == 0 ? layer : 'b';
    };
    for (std::size_t i = 0; i < positions.size(); ++i)
      if (outside[i]) mark(i, 'b');
    for (auto& [column, members] : columns) {
      std::sort(members.begin(), members.end());
      for (std::size_t k = 0; k < members.size(); ++k) {
        if (k < std::size_t(perColumn)) mark(members[k].second, 'f');
        if (k + perColumn >= members.size()) mark(members[k].second, 'k');
      }
    }
    EXPECT_EQ(layersOf(ellipsoids, split), expected);
    EXPECT_EQ(leftOut, positions.size() - expected.size());
    EXPECT_GT(leftOut, positions.size() / 2) << "about twelve centres a texel column: most are left out";
  }
}

// A lamp's columns fit in three quarters of the particles' spacing: the light benchmark's lattices, 2.7
// to 3.0 texels apart, take 2; a Mantaflow liquid's particles, closer than a texel, take 1, as do degenerate
// inputs.
TEST(LightColumns, ALampsColumnsAreNarrowerThanTheParticlesSpacing) {
  EXPECT_EQ(columnSideFor(2.688f, 1.0f), 2);
  EXPECT_EQ(columnSideFor(0.0301f, 0.01f), 2);
  EXPECT_EQ(columnSideFor(0.6f, 1.0f), 1);
  EXPECT_EQ(columnSideFor(4.0f, 1.0f), 3);
  EXPECT_EQ(columnSideFor(1.3f, 1.0f), 1);
  EXPECT_EQ(columnSideFor(0.0f, 1.0f), 1) << "no spacing (no particles)";
  EXPECT_EQ(columnSideFor(1.0f, 0.0f), 64) << "a texel of no size: the largest side";
  EXPECT_EQ(columnSideFor(std::numeric_limits<float>::quiet_NaN(), 1.0f), 1);
  EXPECT_EQ(columnSideFor(1e30f, 1e-30f), 64);
  for (const float spacing : {0.5f, 1.0f, 2.0f, 2.7f, 3.0f, 5.0f, 40.0f}) {
    const int side = columnSideFor(spacing, 1.0f);
    EXPECT_GE(side, 1);
    EXPECT_TRUE(side == 1 || float(side) <= kColumnSpacingFraction * spacing) << spacing;
  }
}

TEST(LightColumns, ColumnsOfFewCentresAndCentresOffTheViewKeepEverything) {
  const Camera view = lightView();
  // Four centres stacked in one column (its two nearest and two farthest are all of them, each in one
  // layer), one behind the view, one beside it and one not a number (kept in both layers).
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<glm::vec3> positions = {{0.05f, 0.05f, 0.0f}, {0.05f, 0.05f, 0.3f}, {0.05f, 0.05f, -0.3f},
                                      {0.05f, 0.05f, 0.6f}, {0.0f, 0.0f, 20.0f},  {30.0f, 0.0f, 0.0f},
                                      {nan, 0.0f, 0.0f}};
  std::vector<EllipsoidInstance> ellipsoids = spheresAt(positions);
  LayerSplit split;
  EXPECT_EQ(keepColumnEnds(ellipsoids, split, view, 2), 0u);
  EXPECT_EQ(ellipsoids.size(), positions.size());
  EXPECT_EQ(split.frontOnly, 2u) << "the column's nearest pair";
  EXPECT_EQ(split.backOnly, 2u) << "the column's farthest pair";

  std::vector<EllipsoidInstance> untouched = spheresAt(positions);
  LayerSplit none{3, 4};
  EXPECT_EQ(keepColumnEnds(untouched, none, view, 0), 0u) << "0: every particle drawn";
  EXPECT_EQ(none.frontOnly, 3u);
  EXPECT_EQ(none.backOnly, 4u);
  std::vector<EllipsoidInstance> empty;
  EXPECT_EQ(keepColumnEnds(empty, none, view, 2), 0u);
}

}  // namespace spindrift
