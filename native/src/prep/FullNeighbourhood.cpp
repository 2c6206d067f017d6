#include "prep/FullNeighbourhood.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "prep/Anisotropy.h"
#include "prep/NeighbourGrid.h"

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
  // which only merges far cells into one bucket; distances are still checked exactly (and the rest density's
  // sample may take a far cell's particles too).
  const auto part = [](std::int64_t v) { return std::uint64_t(v + (1 << 20)) & 0x1FFFFF; };
  return (part(x) << 42) | (part(y) << 21) | part(z);
}

// One cell's particles: a range of SampledNeighbourhoods::memberList.
struct CellMembers {
  const std::uint32_t* first;
  const std::uint32_t* last;
  const std::uint32_t* begin() const { return first; }
  const std::uint32_t* end() const { return last; }
};

// The frame's sample (every k-th liquid particle) and every liquid particle filed into the cells around it:
// all the neighbours a sampled particle has. The cells' members lie in one list, each cell's in index order
// (a vector per cell took a hundred thousand allocations on the bigger bake).
struct SampledNeighbourhoods {
  float cellSize = 0.0f;
  std::vector<std::uint32_t> samples;
  std::unordered_map<std::uint64_t, std::uint32_t> cellIndex;  // a cell's key: its place in memberStart
  std::vector<std::uint32_t> memberStart;                      // each cell's first member; then the end
  std::vector<std::uint32_t> memberList;

  Cell cellOf(const Particles& particles, std::uint32_t i) const {
    const glm::vec3 c = glm::floor(particles.positions[i] / cellSize);
    return Cell{std::int64_t(c.x), std::int64_t(c.y), std::int64_t(c.z)};
  }
  CellMembers membersOf(std::uint64_t key) const {
    const std::uint32_t cell = cellIndex.at(key);
    return {memberList.data() + memberStart[cell], memberList.data() + memberStart[cell + 1]};
  }
  CellMembers members(const Cell& c, int dx, int dy, int dz) const {
    return membersOf(cellKey(c.x + dx, c.y + dy, c.z + dz));
  }
};

SampledNeighbourhoods sampleNeighbourhoods(const Particles& particles, float neighbourRadius) {
  SampledNeighbourhoods sampled;
  std::vector<std::uint32_t> liquid;
  float largestRadius = 0.0f;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (validLiquid(particles, i)) {
      liquid.push_back(std::uint32_t(i));
      largestRadius = std::max(largestRadius, particles.radii[i]);
    }
  if (liquid.empty()) return sampled;
  sampled.cellSize = neighbourRadius * largestRadius;
  const std::size_t stride = std::max<std::size_t>(1, liquid.size() / kSamples);
  for (std::size_t k = 0; k < liquid.size(); k += stride)
    sampled.samples.push_back(liquid[k]);

  // The cells around the samples, then one pass that files every liquid particle lying in one of them.
  for (const std::uint32_t s : sampled.samples) {
    const Cell c = sampled.cellOf(particles, s);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          sampled.cellIndex.try_emplace(cellKey(c.x + dx, c.y + dy, c.z + dz),
                                        std::uint32_t(sampled.cellIndex.size()));
  }
  // Each particle's cell looked up in parallel (the map is only read), then counted and filed in index order.
  constexpr std::uint32_t kNoCell = ~std::uint32_t(0);
  std::vector<std::uint32_t> cellOfParticle(liquid.size(), kNoCell);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, liquid.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& block) {
                      for (std::size_t k = block.begin(); k != block.end(); ++k) {
                        const Cell c = sampled.cellOf(particles, liquid[k]);
                        const auto found = sampled.cellIndex.find(cellKey(c.x, c.y, c.z));
                        if (found != sampled.cellIndex.end()) cellOfParticle[k] = found->second;
                      }
                    });
  sampled.memberStart.assign(sampled.cellIndex.size() + 1, 0);
  for (const std::uint32_t cell : cellOfParticle)
    if (cell != kNoCell) ++sampled.memberStart[cell + 1];
  for (std::size_t cell = 1; cell < sampled.memberStart.size(); ++cell)
    sampled.memberStart[cell] += sampled.memberStart[cell - 1];
  sampled.memberList.resize(sampled.memberStart.back());
  std::vector<std::uint32_t> next(sampled.memberStart.begin(), sampled.memberStart.end() - 1);
  for (std::size_t k = 0; k < liquid.size(); ++k)
    if (cellOfParticle[k] != kNoCell) sampled.memberList[next[cellOfParticle[k]]++] = liquid[k];
  return sampled;
}

float countPercentile(const SampledNeighbourhoods& sampled, const Particles& particles,
                      float neighbourRadius) {
  if (sampled.samples.empty()) return 0.0f;
  std::vector<float> counts(sampled.samples.size());
  tbb::parallel_for(std::size_t(0), counts.size(), [&](std::size_t k) {
    const std::uint32_t s = sampled.samples[k];
    const glm::vec3& p = particles.positions[s];
    const float reach = neighbourRadius * particles.radii[s];
    const Cell c = sampled.cellOf(particles, s);
    int count = 0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz)
          for (const std::uint32_t j : sampled.members(c, dx, dy, dz)) {
            const glm::vec3 d = particles.positions[j] - p;
            count += j != s && glm::dot(d, d) < reach * reach;
          }
    counts[k] = float(count);
  });
  const std::size_t rank = std::min(counts.size() - 1, std::size_t(kFullPercentile * double(counts.size())));
  std::nth_element(counts.begin(), counts.begin() + std::ptrdiff_t(rank), counts.end());
  return counts[rank];
}

// The interior densities of the particles in `centres` (cells of the sample), each shaped from its
// neighbours in the cells around, as a view shapes it without what only its drawing needs (Mantaflow's
// surface, the eye).
std::vector<float> interiorDensities(const SampledNeighbourhoods& sampled, const Particles& particles,
                                     const std::vector<Cell>& centres, const AnisotropySettings& settings) {
  std::unordered_set<std::uint64_t> centreKeys, taken;
  for (const Cell& c : centres)
    centreKeys.insert(cellKey(c.x, c.y, c.z));
  ParticleCloud cloud;
  for (const Cell& c : centres)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const std::uint64_t key = cellKey(c.x + dx, c.y + dy, c.z + dz);
          if (!taken.insert(key).second) continue;
          const bool centre = centreKeys.count(key) > 0;
          for (const std::uint32_t i : sampled.membersOf(key)) {
            const glm::vec3& p = particles.positions[i];
            cloud.x.push_back(p.x);
            cloud.y.push_back(p.y);
            cloud.z.push_back(p.z);
            cloud.radius.push_back(particles.radii[i]);
            cloud.visible.push_back(centre);
          }
        }
  const NeighbourGrid grid(std::move(cloud), sampled.cellSize);
  const ParticleShapes shapes = shapeParticles(grid, settings);
  std::vector<float> interior;
  for (std::size_t i = 0; i < shapes.kinds.size(); ++i)
    if (shapes.kinds[i] == ShapeKind::Interior) interior.push_back(shapes.densities[i]);
  return interior;
}

float restDensityOf(const SampledNeighbourhoods& sampled, const Particles& particles,
                    const LiquidParameters& parameters, float minNeighbours) {
  AnisotropySettings settings = AnisotropySettings::fromParameters(parameters);
  settings.minNeighbours = minNeighbours;
  std::vector<Cell> order;
  std::unordered_set<std::uint64_t> seen;
  for (const std::uint32_t s : sampled.samples) {
    const Cell c = sampled.cellOf(particles, s);
    if (seen.insert(cellKey(c.x, c.y, c.z)).second) order.push_back(c);
  }
  // Batches are shaped two at a time, side by side: each batch's own shaping is too small to keep two threads
  // busy (the bigger bake's 13 batches took 11 ms one after the other). The second's densities are taken
  // only where the first's left too few, so the median is the one batch after batch gives.
  constexpr std::size_t kBatchesAtOnce = 2;
  const auto batch = [&](std::size_t index) {
    const std::size_t first = std::min(order.size(), index * kRestDensityCellBatch);
    const std::size_t last = std::min(order.size(), first + kRestDensityCellBatch);
    return std::vector<Cell>(order.begin() + std::ptrdiff_t(first), order.begin() + std::ptrdiff_t(last));
  };
  std::vector<float> interior;
  for (std::size_t index = 0;
       index * kRestDensityCellBatch < order.size() && interior.size() < kRestDensityInterior;
       index += kBatchesAtOnce) {
    std::vector<float> found[kBatchesAtOnce];
    tbb::parallel_for(std::size_t(0), kBatchesAtOnce, [&](std::size_t k) {
      const std::vector<Cell> cells = batch(index + k);
      if (!cells.empty()) found[k] = interiorDensities(sampled, particles, cells, settings);
    });
    for (std::size_t k = 0; k < kBatchesAtOnce && interior.size() < kRestDensityInterior; ++k)
      interior.insert(interior.end(), found[k].begin(), found[k].end());
  }
  if (interior.size() < kMinInteriorForRestDensity) return 1.0f;
  const auto middle = interior.begin() + std::ptrdiff_t(interior.size() / 2);
  std::nth_element(interior.begin(), middle, interior.end());
  return *middle;
}

}  // namespace

float fullNeighbourCount(const Particles& particles, float neighbourRadius) {
  return countPercentile(sampleNeighbourhoods(particles, neighbourRadius), particles, neighbourRadius);
}

FrameNeighbourhood frameNeighbourhood(const Particles& particles, const LiquidParameters& parameters) {
  const SampledNeighbourhoods sampled = sampleNeighbourhoods(particles, parameters.neighbour_radius);
  FrameNeighbourhood frame;
  frame.fullNeighbours = countPercentile(sampled, particles, parameters.neighbour_radius);
  frame.minNeighbours = appliedMinNeighbours(parameters, frame.fullNeighbours);
  if (parameters.layers != "merged")
    frame.restDensity =
        sampled.samples.empty() ? 1.0f : restDensityOf(sampled, particles, parameters, frame.minNeighbours);
  return frame;
}

float appliedMinNeighbours(const LiquidParameters& parameters, float fullNeighbours) {
  const float absolute = float(parameters.anisotropy_min_neighbours);
  if (!(parameters.anisotropy_min_neighbour_fraction > 0.0f)) return absolute;
  const float relative =
      std::max(kMinCovarianceNeighbours, parameters.anisotropy_min_neighbour_fraction * fullNeighbours);
  return std::min(absolute, relative);
}

}  // namespace spindrift
