// spindrift_bench_prep: the speed of each stage of prepareLiquid on FLIP-like frames of 10k to 1M particles.
// Not a test: it prints a table (median of 5 runs) and exits.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <optional>
#include <random>
#include <vector>

#include <tbb/info.h>

#include "prep/Anisotropy.h"
#include "prep/FullNeighbourhood.h"
#include "prep/LiquidPreparation.h"
#include "prep/LiquidStages.h"

namespace spindrift {
namespace {

constexpr float kRadius = 0.01f;
constexpr float kSpacing = 0.9f * kRadius;
constexpr int kRuns = 5;

// A tank of liquid twice as wide as deep, jittered like FLIP particles, with a wavy free surface and 2% of
// the particles thrown above it as single drops and small clumps.
Particles flipLikeFrame(std::size_t count) {
  std::mt19937 random(42);
  std::uniform_real_distribution<float> jitter(-0.2f * kSpacing, 0.2f * kSpacing);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const std::size_t splashCount = count / 50;
  const int side = int(std::cbrt(double(count - splashCount) / 2.0));
  const float width = float(2 * side) * kSpacing, depth = float(side) * kSpacing;
  const auto surface = [&](float x, float y) {
    return 0.8f * depth + 0.1f * depth * std::sin(6.0f * x / width) * std::cos(4.0f * y / width);
  };
  Particles particles;
  particles.reserve(count);
  for (int i = 0; i < 2 * side && particles.size() < count - splashCount; ++i)
    for (int j = 0; j < side; ++j)
      for (int k = 0; k < 2 * side; ++k) {
        const glm::vec3 position(float(i) * kSpacing + jitter(random), float(j) * kSpacing + jitter(random),
                                 float(k) * kSpacing + jitter(random));
        if (position.z > surface(position.x, position.y)) continue;
        particles.append(position, kRadius, ParticleKind::Liquid, 0.0f, {});
      }
  while (particles.size() < count) {
    const glm::vec3 drop(unit(random) * width, unit(random) * depth, depth + unit(random) * 2.0f * depth);
    const int clump = 1 + int(unit(random) * 4.0f);
    for (int c = 0; c < clump && particles.size() < count; ++c)
      particles.append(drop + glm::vec3(jitter(random), jitter(random), jitter(random)) * 3.0f, kRadius,
                       ParticleKind::Liquid, 0.0f, {});
  }
  return particles;
}

// Wall time and process CPU time (all threads) of one stage, each the median of kRuns. On a machine that
// others share, CPU time shows what the stage costs when the wall time does not.
struct StageTime {
  double wallMs = 0.0;
  double cpuMs = 0.0;
};

StageTime medianTime(const std::function<void()>& run) {
  std::vector<double> wall, cpu;
  for (int r = 0; r < kRuns; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpuStart = std::clock();
    run();
    cpu.push_back(double(std::clock() - cpuStart) * 1000.0 / CLOCKS_PER_SEC);
    wall.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::nth_element(wall.begin(), wall.begin() + kRuns / 2, wall.end());
  std::nth_element(cpu.begin(), cpu.begin() + kRuns / 2, cpu.end());
  return {wall[kRuns / 2], cpu[kRuns / 2]};
}

void benchmark(std::size_t count) {
  const Particles particles = flipLikeFrame(count);
  float extent = 0.0f;
  for (const glm::vec3& position : particles.positions)
    extent = std::max(extent, position.x);
  const Camera camera = Camera::lookAt(1920, 1080, 40.0f, glm::vec3(0.5f, -1.4f, 0.9f) * extent,
                                       glm::vec3(0.5f, 0.25f, 0.1f) * extent, {0, 0, 1});
  const LiquidParameters parameters;
  const AnisotropySettings settings = AnisotropySettings::fromParameters(parameters);

  LiquidCandidates candidates = selectLiquidCandidates(particles, camera, parameters);
  const StageTime select =
      medianTime([&] { candidates = selectLiquidCandidates(particles, camera, parameters); });
  std::optional<NeighbourGrid> grid;
  const StageTime gridBuild = medianTime([&] { grid.emplace(candidates.cloud, candidates.cellSize); });
  ParticleShapes shapes;
  const StageTime shape = medianTime([&] { shapes = shapeParticles(*grid, settings); });
  const StageTime fullCount = medianTime([&] { fullNeighbourCount(particles, parameters.neighbour_radius); });
  FrameNeighbourhood frame;
  const StageTime rest = medianTime([&] { frame = frameNeighbourhood(particles, parameters); });
  const float restDensity = frame.restDensity;
  LiquidPreparation packed;
  const StageTime classify =
      medianTime([&] { classifyAndPack(*grid, shapes, restDensity, parameters, nullptr, packed); });
  LiquidPreparation total;
  const StageTime all = medianTime([&] { total = prepareLiquid(particles, camera, parameters); });

  const auto print = [&](const char* stage, const StageTime& time) {
    std::printf("%9zu  %-9s %8.1f ms %8.1f ms %10.2f M/s\n", particles.size(), stage, time.wallMs, time.cpuMs,
                double(particles.size()) / (time.wallMs * 1e-3) / 1e6);
  };
  print("select", select);
  print("grid", gridBuild);
  print("shape", shape);
  print("N_full", fullCount);
  print("+rho_0", rest);
  print("classify", classify);
  print("total", all);
  std::printf("%9s  aggregates %zu (interior %zu), splashes %zu, culled %zu\n", "", total.aggregates.size(),
              total.isotropicInterior, total.splashes.size(), total.culled);
}

}  // namespace
}  // namespace spindrift

int main() {
  std::printf("spindrift_bench_prep: %d threads, median of %d runs\n", tbb::info::default_concurrency(),
              spindrift::kRuns);
  std::printf("%9s  %-9s %11s %11s %14s\n", "particles", "stage", "wall", "cpu", "particles/s");
  for (std::size_t count : {10000u, 100000u, 1000000u})
    spindrift::benchmark(count);
}
