// The numbers behind a Mantaflow `domain` (docs/mantaflow-caches.md, "The liquid mesh"): how far Mantaflow's
// averaged particle level set stands above a flat body, against the continuum limit integrated here; and how
// far Spindrift's own ellipsoids stand above the same body, with and without liquid.surface_offset.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "prep/LiquidPreparation.h"
#include "scene/MantaflowDomain.h"
#include "spindrift/Camera.h"
#include "spindrift/Parameters.h"
#include "spindrift/Particles.h"

namespace spindrift {
namespace {

// The continuum limit of the averaged level set above the half space z < 0: with weight 1 - d^2 / R^2,
// R = 2 r, the slab at height z of the ball around (0, 0, h) weighs pi (R^2 - (h - z)^2)^2 / (2 R^2), so the
// weighted mean height is a one-dimensional integral; the surface is where h - mean = r.
double continuumFlatOffset(double kernelRadius) {
  const double R = 2.0 * kernelRadius;
  const auto meanHeight = [&](double h) {
    double weight = 0.0, moment = 0.0;
    const int steps = 4000;
    const double low = h - R, high = std::min(0.0, h + R);
    for (int i = 0; i < steps; ++i) {
      const double z = low + (i + 0.5) * (high - low) / steps;
      const double w = std::pow(R * R - (h - z) * (h - z), 2.0);
      weight += w;
      moment += w * z;
    }
    return moment / weight;
  };
  double inside = 0.0, outside = 3.0 * kernelRadius;
  for (int step = 0; step < 60; ++step) {
    const double middle = 0.5 * (inside + outside);
    (middle - meanHeight(middle) < kernelRadius ? inside : outside) = middle;
  }
  return 0.5 * (inside + outside);
}

TEST(MantaflowSurface, AveragedLevelSetAboveAFineLatticeMatchesTheContinuum) {
  for (float kernel : {0.875f, 1.741f, 2.607f}) {
    SCOPED_TRACE(kernel);
    const float spacing = 0.1f;
    // The lattice's top layer lies half a spacing below the continuum's boundary.
    EXPECT_NEAR(mantaflowFlatOffset(kernel, spacing) - 0.5f * spacing, continuumFlatOffset(kernel),
                0.03f * kernel);
  }
}

TEST(MantaflowSurface, BlenderDefaultsStandAboutThreeQuartersOfACellOff) {
  // mesh_particle_radius 2 on a mesh grid twice as fine as the simulation's, particles half a cell apart:
  // in mesh cells r_m = sqrt(3)/2 * 2.01 and the spacing is one mesh cell.
  const LiquidSurfaceFromDomain surface = liquidSurfaceFromDomain({}, 1.0f);
  EXPECT_NEAR(surface.meshKernelRadius, 0.5f * std::sqrt(3.0f) * 2.01f / 2.0f, 1e-5f);
  EXPECT_GT(surface.flatOffset, 0.6f);
  EXPECT_LT(surface.flatOffset, 0.9f);
  EXPECT_NEAR(surface.radius, 0.55f, 1e-6f);
  // A finer mesh grid with the same mesh_particle_radius meshes thinner particles.
  MantaflowDomainSettings coarse;
  coarse.meshScale = 1;
  EXPECT_GT(liquidSurfaceFromDomain(coarse, 1.0f).flatOffset, 1.5f * surface.flatOffset);
}

// The height of an ellipsoid instance's top above its centre: its support along +z.
float topAboveCentre(const EllipsoidInstance& instance) {
  // The rows of the inverse axes matrix are axis_k / a_k: a_k^2 (axis_k . z)^2 = (row_k.z)^2 / |row_k|^4.
  float support = 0.0f;
  for (const glm::vec4& row : instance.inverseAxesRows) {
    const float length = glm::length(glm::vec3(row));
    support += row.z * row.z / std::pow(length, 4.0f);
  }
  return std::sqrt(support);
}

float flatSurfaceAboveTopLayer(float surfaceOffset) {
  // A slab of particles half a cell apart (cell 1), jittered as Mantaflow seeds them, radius 0.55; the
  // surface over its middle is the highest top of the instances there.
  const float spacing = 0.5f, radius = 0.55f;
  Particles particles;
  unsigned state = 12345u;
  const auto jitter = [&] {
    state = state * 1664525u + 1013904223u;
    return (float(state >> 8) / float(1u << 24) - 0.5f) * 0.1f * spacing;
  };
  for (int k = 0; k < 8; ++k)
    for (int j = -14; j <= 14; ++j)
      for (int i = -14; i <= 14; ++i)
        particles.append({i * spacing + jitter(), j * spacing + jitter(), -(k + 0.5f) * spacing + jitter()},
                         radius, ParticleKind::Liquid, 0.0f, {});
  LiquidParameters parameters;
  parameters.surface_offset = surfaceOffset;
  const Camera camera = Camera::lookAt(64, 64, 60.0f, {0, 0, 20}, {0, 0, 0}, {0, 1, 0});
  const LiquidPreparation preparation = prepareLiquid(particles, camera, parameters);
  float top = -1e30f;
  for (const auto* group : {&preparation.aggregates, &preparation.splashes})
    for (const EllipsoidInstance& instance : *group) {
      const glm::vec4& centre = instance.centreAndBoundingRadius;
      if (std::abs(centre.x) > 3.0f || std::abs(centre.y) > 3.0f) continue;
      top = std::max(top, centre.z + topAboveCentre(instance));
    }
  return (top + 0.5f * spacing) / radius;
}

TEST(MantaflowSurface, SpindriftsFlatSurfaceStandsWhereTheDerivationAssumes) {
  const float plain = flatSurfaceAboveTopLayer(0.0f);
  EXPECT_NEAR(plain, kSpindriftFlatOffsetRadii, 0.15f);
  // Growing every axis by s radii moves the flat surface out by s radii.
  EXPECT_NEAR(flatSurfaceAboveTopLayer(1.5f) - plain, 1.5f, 0.05f);
}

}  // namespace
}  // namespace spindrift
