// What every view of a frame shapes its particles by (prep/FullNeighbourhood.h). Yu and Turk's N_epsilon
// relative to the frame's full neighbourhood: a coarsely sampled body (a lattice 1.33 r apart, as the light
// benchmark's and many particle systems' are) has 26 neighbours inside and 17 on a face, so an absolute
// N_epsilon of 25 draws its whole free surface as small spheres. Counts against a brute-force CPU count; the
// faces' shapes with and without the relative rule. The rest density rho_0 against the kernel sum of a
// lattice's interior particle, and the same for views that see all or a corner of the body.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

// Every interior particle of a lattice has the same neighbours, so rho_0 is their density: Yu and Turk's
// sigma / R^3 times the sum of (1 - |d / R|^2)^3 over the particle and its neighbours within R, times r^3.
TEST(FullNeighbourhood, RestDensityIsALatticesInteriorDensity) {
  const Particles particles = lattice(12);
  const LiquidParameters parameters;
  const float neighbourhood = parameters.neighbour_radius * kRadius;
  const glm::vec3 middle = 6.0f * glm::vec3(kSpacing);
  double sum = 0.0;
  for (const glm::vec3& position : particles.positions) {
    const float q = glm::length(position - middle) / neighbourhood;
    if (q < 1.0f) sum += std::pow(1.0 - double(q) * double(q), 3.0);
  }
  const double sigma = 315.0 / (64.0 * 3.14159265358979);
  const double expected = sigma * sum * std::pow(double(kRadius) / double(neighbourhood), 3.0);
  const FrameNeighbourhood frame = frameNeighbourhood(particles, parameters);
  EXPECT_NEAR(frame.restDensity, expected, 1e-4 * expected);
  EXPECT_EQ(frame.fullNeighbours, 26.0f);
  EXPECT_EQ(frame.minNeighbours, 8.0f);
}

// A view that sees a corner of the body splits its splashes at the density a view of the whole body does:
// rho_0 comes from the frame, not from the interior particles a view happens to see.
TEST(FullNeighbourhood, EveryViewOfAFrameSplitsAtTheSameRestDensity) {
  Particles particles;
  unsigned state = 2024;
  const auto next = [&state] {
    return float((state = state * 1664525u + 1013904223u) >> 8) / float(1 << 24);
  };
  for (int n = 0; n < 20000; ++n)  // a jittered slab, sparser towards its top, about half a radius apart
    particles.append(glm::vec3(next(), next(), 0.2f * next() * (1.0f + next())) * glm::vec3(0.6f, 0.6f, 1.0f),
                     kRadius, ParticleKind::Liquid, 0.0f, {});
  const LiquidParameters parameters;
  const Camera whole = Camera::lookAt(64, 64, 60.0f, {0.3f, 0.3f, 1.5f}, {0.3f, 0.3f, 0.1f}, {0, 1, 0});
  const Camera corner = Camera::lookAt(64, 64, 10.0f, {0.05f, 0.05f, 0.6f}, {0.05f, 0.05f, 0.1f}, {0, 1, 0});
  const LiquidPreparation all = prepareLiquid(particles, whole, parameters);
  const LiquidPreparation some = prepareLiquid(particles, corner, parameters);
  ASSERT_GT(some.culled, particles.size() / 2) << "the corner's view must leave most of the body out";
  EXPECT_GT(all.restDensity, 1.0f);
  EXPECT_EQ(some.restDensity, all.restDensity);
  EXPECT_EQ(frameNeighbourhood(particles, parameters).restDensity, all.restDensity);
}

TEST(FullNeighbourhood, RestDensityOfABodyWithoutInteriorIsOneAndOfMergedLayersZero) {
  // A sheet one particle thick has no interior particle: rho_0 is that of particles one radius apart.
  Particles sheet;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      sheet.append(glm::vec3(float(i), float(j), 0.0f) * kSpacing, kRadius, ParticleKind::Liquid, 0.0f, {});
  LiquidParameters parameters;
  EXPECT_EQ(frameNeighbourhood(sheet, parameters).restDensity, 1.0f);
  EXPECT_EQ(frameNeighbourhood(Particles{}, parameters).restDensity, 1.0f) << "no liquid";
  parameters.layers = "merged";
  EXPECT_EQ(frameNeighbourhood(lattice(12), parameters).restDensity, 0.0f) << "merged layers need no density";
}

}  // namespace spindrift
