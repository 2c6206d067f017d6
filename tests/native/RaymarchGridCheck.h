#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gl/GlThread.h"
#include "gl/ShaderLibrary.h"
#include "passes/DensityMaskPass.h"
#include "passes/RaymarchGridPass.h"
#include "prep/RaymarchPreparation.h"

// The binary density grid against a brute-force CPU density: every cell the GPU marks 0 must have density
// below the iso-value at every point of a 5x5x5 lattice spanning the cell (corners and faces included).
namespace raymarch_test {

struct GridCheck {
  std::size_t cells = 0;
  std::size_t markedCells = 0;
  std::size_t crossingCells = 0;  ///< Cells where the sampled density crosses the iso-value.
  std::size_t missedCells = 0;    ///< Cells marked 0 with a sample at or above the iso-value.
};

// Density in units of one particle's peak, sum of (1 - q^2)^3 with q = d / h_j and h_j each particle's w, as
// lib/raymarch_grid.glsl defines it, from a CPU bucket grid of the largest h_j (independent of the GPU's cell
// lists).
class CpuDensity {
 public:
  explicit CpuDensity(const std::vector<glm::vec4>& particles) {
    low_ = glm::vec3(INFINITY);
    glm::vec3 high(-INFINITY);
    side_ = 0.0f;
    for (const glm::vec4& p : particles) {
      low_ = glm::min(low_, glm::vec3(p));
      high = glm::max(high, glm::vec3(p));
      side_ = std::max(side_, p.w);
    }
    size_ = glm::ivec3(glm::floor((high - low_) / side_)) + 1;
    buckets_.resize(std::size_t(size_.x) * size_.y * size_.z);
    for (const glm::vec4& p : particles)
      buckets_[index(bucketOf(glm::vec3(p)))].push_back(p);
  }
  float operator()(const glm::vec3& x) const {
    const glm::ivec3 centre = bucketOf(x);
    float density = 0.0f;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const glm::ivec3 b = centre + glm::ivec3(dx, dy, dz);
          if (glm::any(glm::lessThan(b, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(b, size_)))
            continue;
          for (const glm::vec4& p : buckets_[index(b)]) {
            const float q2 = glm::dot(x - glm::vec3(p), x - glm::vec3(p)) / (p.w * p.w);
            if (q2 < 1.0f) density += (1.0f - q2) * (1.0f - q2) * (1.0f - q2);
          }
        }
    return density;
  }

 private:
  glm::ivec3 bucketOf(const glm::vec3& x) const { return glm::ivec3(glm::floor((x - low_) / side_)); }
  std::size_t index(const glm::ivec3& b) const { return (std::size_t(b.z) * size_.y + b.y) * size_.x + b.x; }
  float side_;
  glm::vec3 low_;
  glm::ivec3 size_;
  std::vector<std::vector<glm::vec4>> buckets_;
};

// `particles`: world position and kernel support h_j (w).
inline GridCheck checkDensityGrid(const std::vector<glm::vec4>& particles,
                                  const spindrift::LiquidParameters& parameters) {
  using namespace spindrift;
  RaymarchPreparation preparation;
  preparation.particles = particles;
  float h = 0.0f;
  glm::vec3 low(INFINITY), high(-INFINITY);
  for (const glm::vec4& p : particles) {
    low = glm::min(low, glm::vec3(p));
    high = glm::max(high, glm::vec3(p));
    h = std::max(h, p.w);
  }
  preparation.smoothingRadius = h;
  preparation.grid = fitRaymarchGrid(low, high, h);
  GlThread thread;
  const std::vector<std::uint8_t> mask = thread.run([&] {
    const ShaderLibrary shaders(findShaderDirectory());
    RaymarchGridPass gridPass(shaders);
    DensityMaskPass maskPass(shaders);
    maskPass.run(gridPass.run(preparation), parameters);
    return maskPass.readCells();
  });
  const RaymarchGrid& grid = preparation.grid;
  const CpuDensity density(particles);
  GridCheck check;
  constexpr int kSamples = 5;
  for (int z = 0; z < grid.size.z; ++z)
    for (int y = 0; y < grid.size.y; ++y)
      for (int x = 0; x < grid.size.x; ++x) {
        const bool marked = mask[(std::size_t(z) * grid.size.y + y) * grid.size.x + x] != 0;
        ++check.cells;
        check.markedCells += marked;
        float lowest = INFINITY, highest = 0.0f;
        for (int k = 0; k < kSamples * kSamples * kSamples; ++k) {
          const glm::vec3 fraction(k % kSamples, (k / kSamples) % kSamples, k / (kSamples * kSamples));
          const glm::vec3 point =
              grid.origin + (glm::vec3(x, y, z) + fraction / float(kSamples - 1)) * grid.cellSize;
          const float value = density(point);
          lowest = std::min(lowest, value);
          highest = std::max(highest, value);
        }
        const bool crossing = lowest < parameters.raymarch_iso && highest >= parameters.raymarch_iso;
        check.crossingCells += crossing;
        check.missedCells += !marked && highest >= parameters.raymarch_iso;
      }
  return check;
}

}  // namespace raymarch_test
