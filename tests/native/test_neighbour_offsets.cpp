// The anisotropy's neighbours (prep/NeighbourOffsets.h): the particles of a particle's candidate cells within
// its neighbourhood R, kept by AVX-512's compress where the CPU has it and by a scalar loop otherwise. Both
// must keep exactly the candidates with |q|^2 < 1, in candidate order, where q = (x_j - x_i) / R is computed
// as the anisotropy's sums compute it: checked against a plain loop over the candidates, on random clouds and
// on candidates exactly on the neighbourhood's boundary.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include <glm/vec3.hpp>

#include "prep/NeighbourOffsets.h"

namespace spindrift {
namespace {

ParticleCloud cloudOf(const std::vector<glm::vec3>& points) {
  ParticleCloud cloud;
  cloud.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    cloud.x[i] = points[i].x, cloud.y[i] = points[i].y, cloud.z[i] = points[i].z;
    cloud.radius[i] = 0.1f, cloud.visible[i] = 1;
  }
  return cloud;
}

// The candidates of `ranges` with |q|^2 < 1, one at a time.
std::vector<std::uint32_t> keptByPlainLoop(const ParticleCloud& cloud, std::uint32_t particle,
                                           float inverseRadius, const std::vector<IndexRange>& ranges) {
  std::vector<std::uint32_t> kept;
  for (const IndexRange& range : ranges)
    for (std::uint32_t j = range.begin; j < range.end; ++j) {
      const float qx = (cloud.x[j] - cloud.x[particle]) * inverseRadius;
      const float qy = (cloud.y[j] - cloud.y[particle]) * inverseRadius;
      const float qz = (cloud.z[j] - cloud.z[particle]) * inverseRadius;
      if (qx * qx + qy * qy + qz * qz < 1.0f) kept.push_back(j);
    }
  return kept;
}

void expectKeeps(const ParticleCloud& cloud, std::uint32_t particle, float inverseRadius,
                 const std::vector<IndexRange>& ranges, NeighbourOffsets::Compaction compaction) {
  const std::vector<std::uint32_t> expected = keptByPlainLoop(cloud, particle, inverseRadius, ranges);
  NeighbourOffsets neighbours;
  neighbours.gather(cloud, particle, inverseRadius, ranges.data(), int(ranges.size()), compaction);
  ASSERT_EQ(neighbours.count(), int(expected.size()));
  for (int k = 0; k < neighbours.count(); ++k) {
    const std::uint32_t j = expected[std::size_t(k)];
    ASSERT_EQ(neighbours.indices()[k], j) << "kept neighbour " << k;
    EXPECT_EQ(neighbours.x()[k], cloud.x[j] - cloud.x[particle]);
    EXPECT_EQ(neighbours.y()[k], cloud.y[j] - cloud.y[particle]);
    EXPECT_EQ(neighbours.z()[k], cloud.z[j] - cloud.z[particle]);
  }
}

constexpr NeighbourOffsets::Compaction kBoth[] = {NeighbourOffsets::Compaction::Fastest,
                                                  NeighbourOffsets::Compaction::Portable};

TEST(NeighbourOffsets, KeepsTheCandidatesWithinTheNeighbourhoodInOrder) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  std::vector<glm::vec3> points(1000);
  for (glm::vec3& point : points)
    point = {coordinate(random), coordinate(random), coordinate(random)};
  const ParticleCloud cloud = cloudOf(points);
  // Ranges of every length from 0 to 40 around the 16-lane blocks, one that ends the cloud, and many at once.
  std::vector<std::vector<IndexRange>> rangeSets;
  for (std::uint32_t length = 0; length <= 40; ++length)
    rangeSets.push_back({{100, 100 + length}});
  rangeSets.push_back({{0, 1000}});
  rangeSets.push_back({{990, 1000}});
  rangeSets.push_back({{0, 17}, {17, 18}, {200, 231}, {500, 500}, {600, 649}, {950, 1000}});
  for (const NeighbourOffsets::Compaction compaction : kBoth)
    for (const std::vector<IndexRange>& ranges : rangeSets)
      for (const std::uint32_t particle : {0u, 105u, 999u})
        for (const float inverseRadius : {1.0f / 0.3f, 1.0f / 0.9f, 1.0f / 3.0f}) {
          SCOPED_TRACE(testing::Message() << "compaction " << int(compaction) << ", particle " << particle
                                          << ", R " << 1.0f / inverseRadius << ", " << ranges.size()
                                          << " ranges from " << ranges[0].begin);
          expectKeeps(cloud, particle, inverseRadius, ranges, compaction);
        }
}

TEST(NeighbourOffsets, LeavesOutCandidatesExactlyOnTheBoundary) {
  // At R = 0.5 along each axis |q|^2 is exactly 1: outside. Kept: the particle itself, the two just inside
  // and (0.2, 0.2, 0.2); (0.3, 0.3, 0.3) lies 0.52 away.
  std::vector<glm::vec3> points = {{0, 0, 0},       {0.5f, 0, 0},     {0, -0.5f, 0},      {0, 0, 0.5f},
                                   {0.4999f, 0, 0}, {0, 0, -0.4999f}, {0.2f, 0.2f, 0.2f}, {0.3f, 0.3f, 0.3f}};
  for (int copy = 0; copy < 3; ++copy)  // more than one block of 16 lanes
    points.insert(points.end(), points.begin(), points.begin() + 8);
  const ParticleCloud cloud = cloudOf(points);
  const std::vector<IndexRange> ranges = {{0, std::uint32_t(points.size())}};
  for (const NeighbourOffsets::Compaction compaction : kBoth) {
    NeighbourOffsets neighbours;
    neighbours.gather(cloud, 0, 2.0f, ranges.data(), 1, compaction);
    EXPECT_EQ(neighbours.count(), 4 * 4);
    expectKeeps(cloud, 0, 2.0f, ranges, compaction);
  }
}

TEST(NeighbourOffsets, NoCandidatesKeepNothing) {
  const ParticleCloud cloud = cloudOf({{0, 0, 0}, {5, 5, 5}});
  const std::vector<IndexRange> far = {{1, 2}};
  for (const NeighbourOffsets::Compaction compaction : kBoth) {
    NeighbourOffsets neighbours;
    neighbours.gather(cloud, 0, 1.0f, far.data(), 1, compaction);
    EXPECT_EQ(neighbours.count(), 0);
    neighbours.gather(cloud, 0, 1.0f, nullptr, 0, compaction);
    EXPECT_EQ(neighbours.count(), 0);
  }
}

}  // namespace
}  // namespace spindrift
