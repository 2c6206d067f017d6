// The numbers behind a Mantaflow `domain` (docs/mantaflow-caches.md, "The liquid mesh"): how far Mantaflow's
// averaged particle level set stands above a flat body, against the continuum limit integrated here; and how
// far Spindrift's own ellipsoids stand above the same body, with and without liquid.surface_offset; and the
// per-particle surface (MantaflowLevelSet, liquid.mesh_kernel_radius) against a brute-force sum over every
// particle, a lone drop and a drop resting on a body.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "SharedViewChecks.h"
#include "prep/FrameLiquidCache.h"
#include "prep/LiquidPreparation.h"
#include "prep/MantaflowSurface.h"
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

float flatSurfaceAboveTopLayer(float surfaceOffset, float meshKernelRadius = 0.0f) {
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
  parameters.mesh_kernel_radius = meshKernelRadius;
  // The derivation's Spindrift surface is Yu and Turk's shapes as they are: a Mantaflow source's own
  // (mesh_kernel_radius > 0) is never grown to the particle radius, and its offset (1.9 r) exceeds that
  // growth.
  parameters.reach_radius = false;
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

// The examples' domain (mesh_scale 1, mesh_particle_radius 2, particle_number 2) in cells: r_m = 1.741, the
// particles half a cell apart, Spindrift's r = 0.55.
constexpr float kKernelCells = 0.5f * 1.7320508f * 2.01f;
constexpr float kSpacing = 0.5f, kRadius = 0.55f;

TEST(MantaflowSurface, PerParticleOffsetsPutAFlatBodyWhereTheUniformOffsetDoes) {
  // On a flat body every particle's own offset is the flat derivation's: the surface stands at Mantaflow's
  // flat offset, as with the uniform offset alone.
  const float flat = mantaflowFlatOffset(kKernelCells, kSpacing) / kRadius;
  const float uniform = flat - kSpindriftFlatOffsetRadii;
  EXPECT_NEAR(flatSurfaceAboveTopLayer(uniform, kKernelCells / kRadius), flat, 0.25f);
  EXPECT_NEAR(flatSurfaceAboveTopLayer(uniform, kKernelCells / kRadius), flatSurfaceAboveTopLayer(uniform),
              0.25f);
}

// A jittered block of particles kSpacing apart: x, y in [-n, n] spacings, `layers` layers below z = 0.
ParticleCloud block(int n, int layers, unsigned seed) {
  ParticleCloud cloud;
  unsigned state = seed;
  const auto jitter = [&] {
    state = state * 1664525u + 1013904223u;
    return (float(state >> 8) / float(1u << 24) - 0.5f) * 0.3f * kSpacing;
  };
  for (int k = 0; k < layers; ++k)
    for (int j = -n; j <= n; ++j)
      for (int i = -n; i <= n; ++i) {
        cloud.x.push_back(i * kSpacing + jitter());
        cloud.y.push_back(j * kSpacing + jitter());
        cloud.z.push_back(-(k + 0.5f) * kSpacing + jitter());
      }
  cloud.radius.assign(cloud.x.size(), kRadius);
  cloud.visible.assign(cloud.x.size(), 1);
  return cloud;
}

void addParticle(ParticleCloud& cloud, const glm::vec3& position) {
  cloud.x.push_back(position.x);
  cloud.y.push_back(position.y);
  cloud.z.push_back(position.z);
  cloud.radius.push_back(kRadius);
  cloud.visible.push_back(1);
}

// φ at `at` summed over every particle (no lumping): the reference the lumped grid is held to.
float exactLevelSet(const ParticleCloud& cloud, const glm::vec3& at, float kernel) {
  const float support = 2.0f * kernel;
  double sum = 0.0, sx = 0.0, sy = 0.0, sz = 0.0;
  for (std::size_t j = 0; j < cloud.size(); ++j) {
    const glm::vec3 d = glm::vec3(cloud.x[j], cloud.y[j], cloud.z[j]) - at;
    const double w = std::max(0.0, 1.0 - double(glm::dot(d, d)) / (support * support));
    sum += w;
    sx += w * d.x;
    sy += w * d.y;
    sz += w * d.z;
  }
  if (sum <= 0.0) return kernel;
  return float(std::sqrt(sx * sx + sy * sy + sz * sz) / sum) - kernel;
}

TEST(MantaflowSurface, ALoneDropReachesOneKernelRadiusAllRound) {
  ParticleCloud cloud;
  addParticle(cloud, {3.0f, -2.0f, 7.0f});
  const MantaflowLevelSet levelSet(cloud, kKernelCells);
  glm::vec3 out;
  EXPECT_NEAR(levelSet.surfaceDistance({3.0f, -2.0f, 7.0f}, 2.0f * kKernelCells, 3, out), kKernelCells,
              1e-3f);
  EXPECT_NEAR(glm::length(out), 1.0f, 1e-5f);
}

TEST(MantaflowSurface, DropsNearABodyReachItsSurfaceOrAreSwallowedAndLoneDropsAreRound) {
  ParticleCloud cloud = block(12, 6, 7u);
  const glm::vec3 resting(0.1f, -0.2f, 0.5f), hovering(-0.3f, 0.4f, 1.6f), far(0.0f, 0.0f, 6.0f);
  for (const glm::vec3& drop : {resting, hovering, far})
    addParticle(cloud, drop);
  const MantaflowLevelSet levelSet(cloud, kKernelCells);
  const float flatSurface =
      mantaflowFlatOffset(kKernelCells, kSpacing) - 0.5f * kSpacing;  // z of the surface
  glm::vec3 out;
  // Below Mantaflow's flat surface (1.27 cells above the top layer, z = 1.02): its blob reaches up to it.
  EXPECT_NEAR(levelSet.surfaceDistance(resting, 1.25f * kKernelCells, 3, out), flatSurface - resting.z, 0.1f);
  EXPECT_GT(out.z, 0.9f) << "out of the body, away from it";
  // Just above it: the body pulls x̄ more than r_m away, Mantaflow draws no bump, nor does Spindrift.
  EXPECT_GT(exactLevelSet(cloud, hovering, kKernelCells), 0.0f) << "the reference swallows it too";
  EXPECT_EQ(levelSet.surfaceDistance(hovering, 1.25f * kKernelCells, 3, out), 0.0f);
  // 3.4 kernel radii up: a lone drop, its blob pulled a little towards the body.
  const float reach = levelSet.surfaceDistance(far, 1.25f * kKernelCells, 3, out);
  EXPECT_GT(reach, 0.8f * kKernelCells);
  EXPECT_LE(reach, 1.25f * kKernelCells);
}

// Where φ = 0 lies from `from` along the unit `direction` by bisecting the exact sum, at most `maxRadius`.
float exactReach(const ParticleCloud& cloud, const glm::vec3& from, const glm::vec3& direction,
                 float maxRadius) {
  if (exactLevelSet(cloud, from + maxRadius * direction, kKernelCells) <= 0.0f) return maxRadius;
  float inside = 0.0f, outside = maxRadius;
  for (int step = 0; step < 30; ++step) {
    const float middle = 0.5f * (inside + outside);
    (exactLevelSet(cloud, from + middle * direction, kKernelCells) <= 0.0f ? inside : outside) = middle;
  }
  return 0.5f * (inside + outside);
}

TEST(MantaflowSurface, ASplashInASheetIsAsThickAsTheSheetNotAsWide) {
  // A sheet one particle thick. Near its edge the neighbours' mean pulls in along the sheet, so the outward
  // direction runs along it, where Mantaflow's surface lies beyond the largest blob: a sphere of that reach
  // stood out of the mesh on both faces. The inscribed sphere's radius is the sheet's half thickness, which
  // the exact sum puts at about r_m.
  ParticleCloud cloud;
  for (int i = -8; i <= 8; ++i)
    for (int j = -8; j <= 8; ++j)
      addParticle(cloud, {i * kSpacing, j * kSpacing, 0.0f});
  const MantaflowLevelSet levelSet(cloud, kKernelCells);
  const float maxRadius = 1.25f * kKernelCells;
  const glm::vec3 nearEdge(6 * kSpacing, 1 * kSpacing, 0.0f);
  glm::vec3 out;
  EXPECT_GT(levelSet.surfaceDistance(nearEdge, maxRadius, 3, out), 0.95f * maxRadius) << "along the sheet";
  EXPECT_GT(out.x, 0.9f) << "away from the sheet's middle";
  const float inscribed = levelSet.inscribedRadius(nearEdge, maxRadius, 3);
  const float thickness = exactReach(cloud, nearEdge, {0.0f, 0.0f, 1.0f}, maxRadius);
  EXPECT_LT(thickness, 0.85f * maxRadius);
  EXPECT_NEAR(inscribed, thickness, 0.1f * kKernelCells);
  // The sphere lies inside the exact surface: no direction leaves it before 0.95 of the radius.
  for (int k = 0; k < 64; ++k) {
    const float z = 1.0f - (k + 0.5f) / 32.0f, ring = std::sqrt(1.0f - z * z), angle = 2.39996323f * k;
    const glm::vec3 direction(ring * std::cos(angle), ring * std::sin(angle), z);
    EXPECT_LE(exactLevelSet(cloud, nearEdge + 0.95f * inscribed * direction, kKernelCells), 0.0f) << k;
  }
  // A lone drop's blob is round: the inscribed sphere is the whole of it.
  ParticleCloud lone;
  addParticle(lone, {1.0f, 2.0f, 3.0f});
  EXPECT_NEAR(MantaflowLevelSet(lone, kKernelCells).inscribedRadius({1.0f, 2.0f, 3.0f}, maxRadius, 3),
              kKernelCells, 1e-3f);
}

TEST(MantaflowSurface, LumpedSurfaceDistancesMatchTheExactSum) {
  // A block with a ridge and stray drops: for particles of the upper layers and the drops, the distance to
  // φ = 0 along the same direction, from the lumped grid and by bisecting the exact sum.
  ParticleCloud cloud = block(10, 5, 99u);
  for (int i = -10; i <= 10; ++i)
    addParticle(cloud, {i * kSpacing, 0.1f * i, 0.5f});
  addParticle(cloud, {2.0f, 2.0f, 2.2f});
  addParticle(cloud, {-3.0f, 1.0f, 3.5f});
  const MantaflowLevelSet levelSet(cloud, kKernelCells);
  const float maxRadius = 1.25f * kKernelCells;
  int compared = 0, agreed = 0;
  float largest = 0.0f;
  for (std::size_t i = 0; i < cloud.size(); i += 7) {
    const glm::vec3 particle(cloud.x[i], cloud.y[i], cloud.z[i]);
    if (particle.z < -1.0f || std::abs(particle.x) > 3.5f || std::abs(particle.y) > 3.5f) continue;
    glm::vec3 out;
    const float lumped = levelSet.surfaceDistance(particle, maxRadius, 3, out);
    const float atParticle = exactLevelSet(cloud, particle, kKernelCells);
    ++compared;
    if ((lumped == 0.0f) == (atParticle >= 0.0f)) ++agreed;
    if (lumped == 0.0f || atParticle >= 0.0f) continue;
    float inside = 0.0f, outside = maxRadius;
    if (exactLevelSet(cloud, particle + maxRadius * out, kKernelCells) <= 0.0f) inside = outside;
    for (int step = 0; step < 30 && inside < outside; ++step) {
      const float middle = 0.5f * (inside + outside);
      (exactLevelSet(cloud, particle + middle * out, kKernelCells) <= 0.0f ? inside : outside) = middle;
    }
    largest = std::max(largest, std::abs(lumped - 0.5f * (inside + outside)));
  }
  EXPECT_GT(compared, 40);
  EXPECT_GE(agreed, compared - 2) << "absorbed by one and not the other";
  // A tenth of a kernel radius is 0.17 cells, 0.32 r: below the 0.5 r edge-bias target.
  EXPECT_LT(largest, 0.1f * kKernelCells);
}

TEST(MantaflowSurface, SplashesTakeTheSizeOfTheirBlobOrDisappear) {
  // A flat body, a drop hovering just above it and a lone drop far above, through prepareLiquid: both are
  // splashes (few neighbours); Mantaflow's surface swallows the hovering one; the lone one is drawn with
  // radius r_m.
  Particles particles;
  const ParticleCloud body = block(12, 6, 5u);
  for (std::size_t i = 0; i < body.size(); ++i)
    particles.append({body.x[i], body.y[i], body.z[i]}, kRadius, ParticleKind::Liquid, 0.0f, {});
  particles.append({0.1f, -0.2f, 1.6f}, kRadius, ParticleKind::Liquid, 0.0f, {});
  particles.append({0.0f, 0.0f, 9.0f}, kRadius, ParticleKind::Liquid, 0.0f, {});
  LiquidParameters parameters;
  parameters.surface_offset = 1.9f;
  const Camera camera = Camera::lookAt(64, 64, 60.0f, {0, -20, 20}, {0, 0, 0}, {0, 0, 1});
  const LiquidPreparation uniform = prepareLiquid(particles, camera, parameters);
  parameters.mesh_kernel_radius = kKernelCells / kRadius;
  const LiquidPreparation sized = prepareLiquid(particles, camera, parameters);
  ASSERT_EQ(uniform.splashes.size(), 2u);
  EXPECT_EQ(sized.splashes.size(), 1u);
  EXPECT_EQ(sized.splashesAbsorbed, 1u);
  ASSERT_EQ(sized.splashes.size(), 1u);
  EXPECT_NEAR(sized.splashes[0].centreAndBoundingRadius.z, 9.0f, 1e-5f);
  EXPECT_NEAR(sized.splashes[0].centreAndBoundingRadius.w, kKernelCells, 0.01f);
}

// The lumped sums as plain scalar loops over every cell (a cell beyond the 2 r_m ball weighs exactly 0): the
// level set's vector form must give the same bits, as each of its lanes sums in the same order.
glm::vec3 scalarOffsetToMean(const ParticleCloud& cloud, float kernelRadius, const glm::vec3& at) {
  const float cellSize = 0.5f * kernelRadius;
  glm::vec3 lower(cloud.x[0], cloud.y[0], cloud.z[0]), upper = lower;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    lower = glm::min(lower, glm::vec3(cloud.x[i], cloud.y[i], cloud.z[i]));
    upper = glm::max(upper, glm::vec3(cloud.x[i], cloud.y[i], cloud.z[i]));
  }
  int cells[3];
  for (int axis = 0; axis < 3; ++axis)
    cells[axis] = int(std::floor((upper[axis] - lower[axis]) / cellSize)) + 1;
  const std::size_t total = std::size_t(cells[0]) * std::size_t(cells[1]) * std::size_t(cells[2]);
  std::vector<float> count(total, 0.0f), x(total, 0.0f), y(total, 0.0f), z(total, 0.0f);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const float position[3] = {cloud.x[i], cloud.y[i], cloud.z[i]};
    int index[3];
    for (int axis = 0; axis < 3; ++axis)
      index[axis] = std::clamp(int((position[axis] - lower[axis]) / cellSize), 0, cells[axis] - 1);
    const std::size_t cell = (std::size_t(index[0]) * cells[1] + index[1]) * cells[2] + index[2];
    count[cell] += 1.0f;
    x[cell] += position[0];
    y[cell] += position[1];
    z[cell] += position[2];
  }
  const float support = 2.0f * kernelRadius, inverseSupportSquared = 1.0f / (support * support);
  float sum = 0.0f, sx = 0.0f, sy = 0.0f, sz = 0.0f;
  for (std::size_t cell = 0; cell < total; ++cell) {
    if (count[cell] == 0.0f) continue;
    const float dx = x[cell] / count[cell] - at.x, dy = y[cell] / count[cell] - at.y;
    const float dz = z[cell] / count[cell] - at.z;
    const float weight =
        count[cell] * std::max(0.0f, 1.0f - (dx * dx + dy * dy + dz * dz) * inverseSupportSquared);
    sum += weight;
    sx += weight * dx;
    sy += weight * dy;
    sz += weight * dz;
  }
  return sum > 0.0f ? glm::vec3(sx, sy, sz) / sum : glm::vec3(0.0f);
}

TEST(MantaflowSurface, LumpedSumsAreBitForBitTheScalarSums) {
  ParticleCloud cloud = block(10, 5, 11u);
  for (const glm::vec3& drop : {glm::vec3(0.3f, 0.2f, 1.2f), glm::vec3(-2.0f, 1.0f, 0.6f)})
    addParticle(cloud, drop);
  const MantaflowLevelSet levelSet(cloud, kKernelCells);
  unsigned state = 99u;
  const auto unit = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24) - 0.5f;
  };
  int compared = 0;
  for (std::size_t i = 0; i < cloud.size(); i += 7) {
    const glm::vec3 at = glm::vec3(cloud.x[i], cloud.y[i], cloud.z[i]) +
                         kKernelCells * glm::vec3(unit(), unit(), unit() + 0.5f);
    glm::vec3 offset;
    levelSet.offsetToMean(at, offset);
    const glm::vec3 expected = scalarOffsetToMean(cloud, kKernelCells, at);
    ASSERT_EQ(offset.x, expected.x) << "at particle " << i;
    ASSERT_EQ(offset.y, expected.y) << "at particle " << i;
    ASSERT_EQ(offset.z, expected.z) << "at particle " << i;
    ++compared;
  }
  EXPECT_GT(compared, 100);
}

TEST(MantaflowSurface, SampledSumsFollowTheExactOnesAndDoNotDependOnWhichThreadMadeThem) {
  // The searches read x̄ interpolated between sums made once at the corners of a lattice of r_m / 2, from
  // several threads at once. Near the body's surface (where φ = 0 is searched) the interpolated x̄ stays
  // within a few hundredths of r_m of the sum made at the point itself; every thread order gives the same
  // bits.
  ParticleCloud cloud = block(10, 5, 23u);
  for (int i = -10; i <= 10; ++i)
    addParticle(cloud, {i * kSpacing, 0.1f * i, 0.5f});
  unsigned state = 5u;
  const auto unit = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24) - 0.5f;
  };
  std::vector<glm::vec3> points;
  for (std::size_t i = 0; i < cloud.size(); i += 3)
    points.push_back(glm::vec3(cloud.x[i], cloud.y[i], cloud.z[i]) +
                     kKernelCells * glm::vec3(unit(), unit(), unit() + 0.5f));
  const MantaflowLevelSet alone(cloud, kKernelCells), shared(cloud, kKernelCells);
  std::vector<glm::vec3> inOrder(points.size()), inParallel(points.size());
  std::vector<char> nearInOrder(points.size()), nearInParallel(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    nearInOrder[k] = alone.sampledOffsetToMean(points[k], inOrder[k]);
  // Backwards and from every thread at once: other corners are summed first, some by two threads.
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
    const std::size_t back = points.size() - 1 - k;
    nearInParallel[back] = shared.sampledOffsetToMean(points[back], inParallel[back]);
  });
  int nearSurface = 0;
  float largest = 0.0f;
  for (std::size_t k = 0; k < points.size(); ++k) {
    ASSERT_EQ(nearInOrder[k], nearInParallel[k]) << k;
    ASSERT_EQ(inOrder[k], inParallel[k]) << k;
    glm::vec3 exact;
    const bool near = alone.offsetToMean(points[k], exact);
    ASSERT_EQ(bool(nearInOrder[k]), near) << k;
    const float phi = glm::length(exact) - kKernelCells;
    if (!near || std::abs(phi) > 0.5f * kKernelCells) continue;
    ++nearSurface;
    largest = std::max(largest, glm::length(inOrder[k] - exact));
  }
  EXPECT_GT(nearSurface, 50);
  EXPECT_LT(largest, 0.05f * kKernelCells);
}

TEST(MantaflowSurface, LatticeNodesSumTheSameCellsAsAnyPoint) {
  // A node of the sampled lattice sums a fixed stencil of cells about its own (prep/MantaflowSurface.cpp), in
  // another order than offsetToMean's chords: at a node the two agree to float rounding, inside the body, at
  // its surface, outside it and at the lattice's edge, where some of the stencil lies outside the cells. The
  // cells start at the cloud's lowest point, so a lone drop below it moves where in its cell every node lies:
  // four such places are tried.
  const float spacing = 0.5f * kKernelCells;  // the lattice's nodes lie at multiples of r_m / 2
  for (const float shift : {0.0f, 0.25f, 0.5f, 0.75f}) {
    ParticleCloud cloud = block(10, 5, 31u);
    for (const glm::vec3& drop : {glm::vec3(0.3f, 0.2f, 1.2f), glm::vec3(-2.0f, 1.0f, 0.6f)})
      addParticle(cloud, drop);
    addParticle(cloud, glm::vec3(-6.0f - shift * spacing));
    const MantaflowLevelSet levelSet(cloud, kKernelCells);
    int compared = 0, near = 0;
    float largest = 0.0f;
    for (int i = -8; i <= 14; ++i)
      for (int j = -8; j <= 14; ++j)
        for (int k = -8; k <= 10; k += 2) {
          const glm::vec3 node = spacing * glm::vec3(i, j, k);
          glm::vec3 sampled, exact;
          const bool sampledNear = levelSet.sampledOffsetToMean(node, sampled);
          const bool exactNear = levelSet.offsetToMean(node, exact);
          ASSERT_EQ(sampledNear, exactNear) << i << " " << j << " " << k << " shift " << shift;
          ++compared;
          if (!exactNear) continue;
          ++near;
          largest = std::max(largest, glm::length(sampled - exact));
        }
    EXPECT_GT(near, 500) << "shift " << shift;
    EXPECT_GT(compared - near, 500) << "shift " << shift;
    EXPECT_LT(largest, 1e-5f * kKernelCells) << "shift " << shift;
  }
}

TEST(MantaflowSurface, AFrameSurfaceSharedByItsViewsChangesNoViewsResult) {
  // A body with a ridge and drops over it, seen by an oblique camera and from above (both see every particle:
  // they share the frame's surface and each other's searches) and from close by (it culls, so it builds its
  // own): every view's ellipsoids are bit for bit those it gets alone, in any order of the views.
  Particles particles;
  const ParticleCloud body = block(12, 6, 7u);
  for (std::size_t i = 0; i < body.size(); ++i)
    particles.append({body.x[i], body.y[i], body.z[i]}, kRadius, ParticleKind::Liquid, 0.0f, {});
  for (int i = -8; i <= 8; ++i)
    particles.append({i * kSpacing, 0.1f * float(i % 3), 0.3f}, kRadius, ParticleKind::Liquid, 0.0f, {});
  for (const glm::vec3& drop :
       {glm::vec3(0.1f, -0.2f, 1.6f), glm::vec3(2.0f, 3.0f, 0.9f), glm::vec3(0, 0, 9)})
    particles.append(drop, kRadius, ParticleKind::Liquid, 0.0f, {});
  LiquidParameters parameters;
  parameters.surface_offset = 1.9f;
  parameters.mesh_kernel_radius = kKernelCells / kRadius;
  const Camera views[] = {Camera::lookAt(64, 64, 60.0f, {0, -20, 20}, {0, 0, 0}, {0, 0, 1}),
                          Camera::lookAt(64, 64, 60.0f, {0.5f, 0.5f, 30}, {0, 0, 0}, {0, 1, 0}),
                          Camera::lookAt(64, 64, 40.0f, {5, -1, 1}, {7, 0, 0}, {0, 0, 1})};
  const std::vector<LiquidPreparation> alone = shared_views::expectSharedViewsGetWhatTheyGetAlone(
      particles, parameters, views,
      [](const LiquidPreparation& shared, const LiquidPreparation& single, const FrameLiquidCache& frame,
         int view, const std::vector<int>&) {
        EXPECT_EQ(shared.splashesAbsorbed, single.splashesAbsorbed);
        EXPECT_TRUE(frame.search.has_value() || view == 2)
            << "built by the first view that sees every particle";
      });
  EXPECT_GT(alone[0].splashes.size(), 0u);
}

}  // namespace
}  // namespace spindrift
