// Yu and Turk's N_epsilon relative to the frame's full neighbourhood (prep/FullNeighbourhood.h): a coarsely
// sampled body (a lattice 1.33 r apart, as the light benchmark's and many particle systems' are) has 26
// neighbours inside and 17 on a face, so an absolute N_epsilon of 25 draws its whole free surface as small
// spheres. Counts against a brute-force CPU count; the faces' shapes with and without the relative rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include <glm/geometric.hpp>

#include "prep/FullNeighbourhood.h"
#include "prep/LiquidPreparation.h"

namespace spindrift {
namespace {

constexpr float kRadius = 0.03f, kSpacing = 0.04f;  // the light benchmark's lattice

Particles lattice(int side) {
  Particles particles;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < side; ++k)
        particles.append(glm::vec3(float(i), float(j), float(k)) * kSpacing, kRadius, ParticleKind::Liquid,
                         0.0f, {});
  return particles;
}

// Every particle's neighbour count within R, by brute force, and its 90th percentile.
float bruteForceFullNeighbours(const Particles& particles, float neighbourRadius) {
  std::vector<float> counts;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const float reach = neighbourRadius * particles.radii[i];
    int count = 0;
    for (std::size_t j = 0; j < particles.size(); ++j) {
      const glm::vec3 d = particles.positions[j] - particles.positions[i];
      count += j != i && glm::dot(d, d) < reach * reach;
    }
    counts.push_back(float(count));
  }
  std::sort(counts.begin(), counts.end());
  return counts[std::size_t(0.9 * double(counts.size()))];
}

}  // namespace

TEST(FullNeighbourhood, ALatticesInteriorHoldsItsFullNeighbourhood) {
  const Particles particles = lattice(10);
  const LiquidParameters parameters;
  // R = 2.5 r = 1.875 spacings: the 3 x 3 x 3 block around a particle, itself not counted.
  EXPECT_EQ(bruteForceFullNeighbours(particles, parameters.neighbour_radius), 26.0f);
  EXPECT_EQ(fullNeighbourCount(particles, parameters.neighbour_radius), 26.0f);
}

TEST(FullNeighbourhood, SampledCountMatchesBruteForceOnAJitteredBody) {
  Particles particles;
  unsigned state = 12345;
  const auto next = [&state] {
    return float((state = state * 1664525u + 1013904223u) >> 8) / float(1 << 24);
  };
  for (int n = 0; n < 6000; ++n)  // a ball of water, 0.5 across, particles 0.8 r apart on average
    for (;;) {
      const glm::vec3 p(next() - 0.5f, next() - 0.5f, next() - 0.5f);
      if (glm::dot(p, p) > 0.25f) continue;
      particles.append(p * 0.5f, kRadius, ParticleKind::Liquid, 0.0f, {});
      break;
    }
  const LiquidParameters parameters;
  const float exact = bruteForceFullNeighbours(particles, parameters.neighbour_radius);
  EXPECT_NEAR(fullNeighbourCount(particles, parameters.neighbour_radius), exact, 0.05f * exact);
}

TEST(FullNeighbourhood, AppliedThresholdKeepsYuAndTurksWhereTheBodyIsDense) {
  LiquidParameters parameters;  // N_epsilon 25, fraction 0.25
  EXPECT_EQ(appliedMinNeighbours(parameters, 108.0f), 25.0f) << "the dam-break example's frame";
  EXPECT_EQ(appliedMinNeighbours(parameters, 26.0f), 8.0f) << "a lattice 1.33 r apart: never below 8";
  EXPECT_EQ(appliedMinNeighbours(parameters, 60.0f), 15.0f);
  EXPECT_EQ(appliedMinNeighbours(parameters, 0.0f), 8.0f) << "a frame without liquid";
  parameters.anisotropy_min_neighbour_fraction = 0.0f;
  EXPECT_EQ(appliedMinNeighbours(parameters, 26.0f), 25.0f) << "0: Yu and Turk's as given";
  parameters.anisotropy_min_neighbour_fraction = 0.25f;
  parameters.anisotropy_min_neighbours = 5;
  EXPECT_EQ(appliedMinNeighbours(parameters, 26.0f), 5.0f) << "a lower N_epsilon is kept";
}

// The lattice's face particles (17 neighbours) are flat ellipsoids with the relative rule, spheres of k_n r
// without it; the prepared view reports what it applied.
TEST(FullNeighbourhood, ALatticesFacesAreFlatEllipsoidsNotSmallSpheres) {
  const Particles particles = lattice(10);
  const Camera camera = Camera::lookAt(64, 64, 40.0f, {0.18f, 0.18f, 2.0f}, {0.18f, 0.18f, 0.18f}, {0, 1, 0});
  const auto topFaceSemiAxes = [&](const LiquidPreparation& preparation) {
    std::vector<float> shortest;
    for (const EllipsoidInstance& instance : preparation.aggregates) {
      const glm::vec3 centre(instance.centreAndBoundingRadius);
      if (std::abs(centre.z - 9 * kSpacing) > 1e-5f || centre.x < 2 * kSpacing || centre.x > 7 * kSpacing ||
          centre.y < 2 * kSpacing || centre.y > 7 * kSpacing)
        continue;  // the top face's inner particles
      float smallest = 1e9f, largest = 0.0f;
      for (int k = 0; k < 3; ++k) {
        const float semiAxis = 1.0f / glm::length(glm::vec3(instance.inverseAxesRows[k]));
        smallest = std::min(smallest, semiAxis);
        largest = std::max(largest, semiAxis);
      }
      shortest.push_back(smallest / largest);
      EXPECT_GT(largest, 0.5f * kRadius + 1e-6f);
    }
    return shortest;
  };
  LiquidParameters parameters;
  parameters.layers = "merged";  // every particle an aggregate, so each is in the list
  const LiquidPreparation relative = prepareLiquid(particles, camera, parameters);
  EXPECT_EQ(relative.fullNeighbours, 26.0f);
  EXPECT_EQ(relative.minNeighboursApplied, 8.0f);
  const std::vector<float> flat = topFaceSemiAxes(relative);
  ASSERT_EQ(flat.size(), 36u);
  for (const float ratio : flat)
    EXPECT_LT(ratio, 0.8f) << "a face particle is flattened across the face";

  parameters.anisotropy_min_neighbour_fraction = 0.0f;
  const LiquidPreparation absolute = prepareLiquid(particles, camera, parameters);
  EXPECT_EQ(absolute.minNeighboursApplied, 25.0f);
  int spheres = 0;
  for (const EllipsoidInstance& instance : absolute.aggregates)
    spheres += std::abs(instance.centreAndBoundingRadius.w -
                        parameters.anisotropy_isotropic_scale * kRadius) < 1e-6f;
  EXPECT_GE(spheres, 6 * 64) << "every face particle is a sphere of k_n r";
}

}  // namespace spindrift
