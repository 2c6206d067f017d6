// liquid.relax_surface (prep/SurfaceRelaxation.h): surface particles below the smooth surface through their
// neighbours rise onto it. Checked against the shapes the particles sample, computed here: a sphere (a
// lattice ball's outermost particles come to lie at one distance from its centre), a box (no particle leaves
// it, so faces stay flat and edges sharp), and inputs it must leave alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "LiquidTestScenes.h"
#include "prep/SurfaceRelaxation.h"
#include "spindrift/Threads.h"

namespace spindrift {
namespace {

using liquid_test::block;
using liquid_test::latticeBall;
using liquid_test::particlesOf;

constexpr float kSpacing = 0.04f;
constexpr float kRadius = 0.03f;

// The distances from the centre of the particles that lay within a spacing of the outermost before the
// relaxation (a lattice's terraced shell: its outer layer and, at each terrace, the layer under it): their
// 10th to 90th percentile range and their median.
struct Shell {
  float spread = 0.0f;
  float median = 0.0f;
};

Shell outerShell(const Particles& before, const Particles& particles, const glm::vec3& centre) {
  float farthest = 0.0f;
  for (const glm::vec3& p : before.positions)
    farthest = std::max(farthest, glm::distance(p, centre));
  std::vector<float> shell;
  for (std::size_t i = 0; i < before.size(); ++i)
    if (glm::distance(before.positions[i], centre) > farthest - kSpacing)
      shell.push_back(glm::distance(particles.positions[i], centre));
  std::sort(shell.begin(), shell.end());
  const auto at = [&](double q) { return shell[std::size_t(q * double(shell.size() - 1))]; };
  return {at(0.9) - at(0.1), at(0.5)};
}

// Every particle's move, checked: finite, at most three quarters of the measured spacing, and only liquid
// moves.
void expectBoundedMoves(const Particles& before, const Particles& after,
                        const SurfaceRelaxationStats& stats) {
  ASSERT_EQ(before.size(), after.size());
  std::size_t moved = 0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    const glm::vec3 move = after.positions[i] - before.positions[i];
    ASSERT_TRUE(std::isfinite(move.x + move.y + move.z)) << i;
    EXPECT_LE(glm::length(move), kMaxRaiseSpacings * stats.spacing * 1.001f) << i;
    if (before.kinds[i] != ParticleKind::Liquid) EXPECT_EQ(move, glm::vec3(0.0f)) << i;
    moved += glm::length(move) > 0.0f;
    EXPECT_EQ(before.radii[i], after.radii[i]);
    EXPECT_EQ(before.kinds[i], after.kinds[i]);
  }
  EXPECT_EQ(moved, stats.raised);
}

}  // namespace

TEST(SurfaceRelaxation, ALatticeBallsOutermostParticlesComeToLieOnASphere) {
  const glm::vec3 centre(0.013f, -0.007f, 0.65f);  // off the lattice's nodes, as a scene's ball is
  const Particles ball = latticeBall(centre, 0.5f, kSpacing, kRadius);
  SurfaceRelaxationStats stats;
  const Particles relaxed = relaxLiquidSurface(ball, LiquidParameters{}, stats);
  EXPECT_EQ(stats.notApplied, "");
  EXPECT_NEAR(stats.spacing, kSpacing, 0.1f * kSpacing);
  EXPECT_GT(stats.raised, stats.surfaceParticles / 4);
  expectBoundedMoves(ball, relaxed, stats);
  // No particle sinks: on a sphere, none comes nearer its centre.
  for (std::size_t i = 0; i < ball.size(); ++i)
    EXPECT_GE(glm::distance(relaxed.positions[i], centre), glm::distance(ball.positions[i], centre) - 1e-5f);
  const Shell terraced = outerShell(ball, ball, centre), smooth = outerShell(ball, relaxed, centre);
  // A lattice's shell is most of a spacing deep; the relaxed one half of that at most.
  EXPECT_GT(terraced.spread, 0.5f * kSpacing);
  EXPECT_LT(smooth.spread, 0.5f * terraced.spread);
  // ... and it stands where the outermost particles stood, a radius inside the sphere.
  EXPECT_NEAR(smooth.median, 0.5f - kRadius, 0.5f * kSpacing);
}

TEST(SurfaceRelaxation, ABoxKeepsItsFlatFacesAndSharpEdges) {
  const glm::vec3 low(-0.4f, -0.4f, 0.0f), high(0.4f, 0.4f, 0.4f);
  const Particles box = particlesOf(block(low, high, kSpacing), kRadius);
  SurfaceRelaxationStats stats;
  const Particles relaxed = relaxLiquidSurface(box, LiquidParameters{}, stats);
  EXPECT_EQ(stats.notApplied, "");
  expectBoundedMoves(box, relaxed, stats);
  // A face's particles define its plane and stay in it; near an edge the fit bends round it, and the
  // particles a spacing or two from it rise a little above the face (0.10 spacings as built), never by 0.15.
  const float tolerance = 0.15f * kSpacing;
  for (const glm::vec3& p : relaxed.positions) {
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, low - tolerance))) << p.x << " " << p.y << " " << p.z;
    EXPECT_TRUE(glm::all(glm::lessThanEqual(p, high + tolerance))) << p.x << " " << p.y << " " << p.z;
  }
  // Away from the edges (beyond the fit's five spacings) every particle is where it was, to rounding.
  for (std::size_t i = 0; i < box.size(); ++i) {
    const glm::vec3 p = box.positions[i];
    const glm::vec3 fromEdges = glm::min(p - low, high - p);
    int nearFaces = 0;
    for (int k = 0; k < 3; ++k)
      nearFaces += fromEdges[k] < 5.5f * kSpacing;
    if (nearFaces <= 1)
      EXPECT_LT(glm::distance(relaxed.positions[i], p), 1e-6f) << p.x << " " << p.y << " " << p.z;
  }
}

TEST(SurfaceRelaxation, AJitteredBallMovesBoundedAndTheSameWithAnyThreadCount) {
  Particles ball = latticeBall(glm::vec3(0.0f), 0.4f, kSpacing, kRadius);
  std::mt19937 random(11);
  std::uniform_real_distribution<float> jitter(-0.3f * kSpacing, 0.3f * kSpacing);
  for (glm::vec3& p : ball.positions)
    p += glm::vec3(jitter(random), jitter(random), jitter(random));
  ball.append(glm::vec3(2.0f), kRadius, ParticleKind::Foam, 10.0f, glm::vec3(0.0f));  // a foam particle stays
  SurfaceRelaxationStats stats, alone;
  const Particles relaxed = relaxLiquidSurface(ball, LiquidParameters{}, stats);
  expectBoundedMoves(ball, relaxed, stats);
  EXPECT_GT(stats.raised, 0u);
  Particles oneThread;
  {
    const WorkerThreadLimit limit(1);
    oneThread = relaxLiquidSurface(ball, LiquidParameters{}, alone);
  }
  EXPECT_EQ(relaxed.positions, oneThread.positions);
}

TEST(SurfaceRelaxation, ASheetOneParticleThickStaysInItsPlaneAndRectangle) {
  // Inside the sheet every particle has the same neighbourhood, at full density: only its rim is a surface,
  // whose particles may move along the sheet, never out of it, and past the rim by 0.15 of the spacing it
  // measures at most (a sheet's is its particles' in-plane spacing, 1.3 times the lattice's).
  const glm::vec3 low(-0.5f, -0.5f, 0.0f), high(0.5f, 0.5f, 0.0f);
  const Particles sheet = particlesOf(block(low, high, kSpacing), kRadius);
  SurfaceRelaxationStats stats;
  const Particles relaxed = relaxLiquidSurface(sheet, LiquidParameters{}, stats);
  expectBoundedMoves(sheet, relaxed, stats);
  for (std::size_t i = 0; i < sheet.size(); ++i) {
    const glm::vec3 p = relaxed.positions[i];
    EXPECT_NEAR(p.z, 0.0f, 1e-6f) << i;
    EXPECT_GE(p.x, low.x - 0.15f * stats.spacing);
    EXPECT_LE(p.x, high.x + 0.15f * stats.spacing);
    EXPECT_GE(p.y, low.y - 0.15f * stats.spacing);
    EXPECT_LE(p.y, high.y + 0.15f * stats.spacing);
    if (std::abs(sheet.positions[i].x) < 0.3f && std::abs(sheet.positions[i].y) < 0.3f)
      EXPECT_LT(glm::distance(p, sheet.positions[i]), 1e-6f) << "inside the sheet";
  }
}

TEST(SurfaceRelaxation, SprayFewParticlesAndCoincidentParticlesAreLeftAsTheyAre) {
  // Spray: particles far apart, no body.
  std::vector<glm::vec3> spray;
  for (int i = 0; i < 200; ++i)
    spray.emplace_back(float(i), float(i % 7), 0.0f);
  SurfaceRelaxationStats stats;
  const Particles sprayParticles = particlesOf(spray, kRadius);
  EXPECT_EQ(relaxLiquidSurface(sprayParticles, LiquidParameters{}, stats).positions,
            sprayParticles.positions);
  EXPECT_NE(stats.notApplied.find("no body"), std::string::npos) << stats.notApplied;

  const Particles few = latticeBall(glm::vec3(0.0f), 0.08f, kSpacing, kRadius);
  ASSERT_LT(few.size(), 64u);
  EXPECT_EQ(relaxLiquidSurface(few, LiquidParameters{}, stats).positions, few.positions);
  EXPECT_EQ(stats.notApplied, "fewer than 64 liquid particles");

  // A thousand particles at one point: no spacing, no gradient.
  const Particles coincident = particlesOf(std::vector<glm::vec3>(1000, glm::vec3(0.25f)), kRadius);
  const Particles relaxed = relaxLiquidSurface(coincident, LiquidParameters{}, stats);
  EXPECT_EQ(relaxed.positions, coincident.positions);
  EXPECT_EQ(stats.raised, 0u);
}

TEST(SurfaceRelaxation, OnlyWithoutMantaflowsSurfaceAndWhenAsked) {
  LiquidParameters parameters;
  EXPECT_TRUE(relaxesSurface(parameters));
  parameters.mesh_kernel_radius = 2.0f;
  EXPECT_FALSE(relaxesSurface(parameters));
  parameters.mesh_kernel_radius = 0.0f;
  parameters.relax_surface = false;
  EXPECT_FALSE(relaxesSurface(parameters));
}

}  // namespace spindrift
