#include "prep/FullNeighbourhood.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace spindrift {
namespace {

constexpr std::size_t kSamples = 1024;
constexpr double kFullPercentile = 0.9;
// A covariance from fewer points than a cube's corners is ruled by where those few happen to lie.
constexpr float kMinCovarianceNeighbours = 8.0f;

bool validLiquid(const Particles& particles, std::size_t i) {
  const glm::vec3& p = particles.positions[i];
  const float radius = particles.radii[i];
  return particles.kinds[i] == ParticleKind::Liquid && radius > 0.0f && std::isfinite(radius) &&
         std::isfinite(p.x + p.y + p.z);
}

struct Cell {
  std::int64_t x, y, z;
};

std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  // 21 bits per axis (offset to be non-negative): a frame spanning two million neighbourhoods per axis wraps,
  // which only merges far cells into one bucket; distances are still checked exactly.
  const auto part = [](std::int64_t v) { return std::uint64_t(v + (1 << 20)) & 0x1FFFFF; };
  return (part(x) << 42) | (part(y) << 21) | part(z);
}

}  // namespace

float fullNeighbourCount(const Particles& particles, float neighbourRadius) {
  std::vector<std::uint32_t> liquid;
  float largestRadius = 0.0f;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (validLiquid(particles, i)) {
      liquid.push_back(std::uint32_t(i));
      largestRadius = std::max(largestRadius, particles.radii[i]);
    }
  if (liquid.empty()) return 0.0f;
  const float cellSize = neighbourRadius * largestRadius;
  const auto cellOf = [&](std::uint32_t i) {
    const glm::vec3 c = glm::floor(particles.positions[i] / cellSize);
    return Cell{std::int64_t(c.x), std::int64_t(c.y), std::int64_t(c.z)};
  };
  const std::size_t stride = std::max<std::size_t>(1, liquid.size() / kSamples);
  std::vector<std::uint32_t> samples;
  for (std::size_t k = 0; k < liquid.size(); k += stride)
    samples.push_back(liquid[k]);

  // The cells around the samples, then one pass that files every liquid particle lying in one of them.
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  for (const std::uint32_t s : samples) {
    const Cell c = cellOf(s);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          cells[cellKey(c.x + dx, c.y + dy, c.z + dz)];
  }
  for (const std::uint32_t i : liquid) {
    const Cell c = cellOf(i);
    const auto found = cells.find(cellKey(c.x, c.y, c.z));
    if (found != cells.end()) found->second.push_back(i);
  }

  std::vector<float> counts;
  counts.reserve(samples.size());
  for (const std::uint32_t s : samples) {
    const glm::vec3& p = particles.positions[s];
    const float reach = neighbourRadius * particles.radii[s];
    const Cell c = cellOf(s);
    int count = 0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          for (const std::uint32_t j : cells.at(cellKey(c.x + dx, c.y + dy, c.z + dz))) {
            const glm::vec3 d = particles.positions[j] - p;
            count += j != s && glm::dot(d, d) < reach * reach;
          }
    counts.push_back(float(count));
  }
  const std::size_t rank = std::min(counts.size() - 1, std::size_t(kFullPercentile * double(counts.size())));
  std::nth_element(counts.begin(), counts.begin() + std::ptrdiff_t(rank), counts.end());
  return counts[rank];
}

float appliedMinNeighbours(const LiquidParameters& parameters, float fullNeighbours) {
  const float absolute = float(parameters.anisotropy_min_neighbours);
  if (!(parameters.anisotropy_min_neighbour_fraction > 0.0f)) return absolute;
  const float relative =
      std::max(kMinCovarianceNeighbours, parameters.anisotropy_min_neighbour_fraction * fullNeighbours);
  return std::min(absolute, relative);
}

}  // namespace spindrift
