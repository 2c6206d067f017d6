#include "prep/LiquidPreparation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "prep/Anisotropy.h"
#include "prep/FrameLiquidCache.h"
#include "prep/FullNeighbourhood.h"
#include "prep/LiquidStages.h"
#include "prep/MantaflowSurface.h"
#include "prep/ViewFrustum.h"

namespace spindrift {
namespace {

using Clock = std::chrono::steady_clock;

double millisecondsBetween(Clock::time_point start, Clock::time_point end) {
  return std::chrono::duration<double, std::milli>(end - start).count();
}

// Ineligible: not a liquid particle, or one without a finite position and a positive finite radius.
enum CandidateRole : std::uint8_t {
  kIneligible = 0,
  kOutside = 1,
  kNeighbourOnly = 2,
  kBehindSolids = 3,  // a neighbour only
  kVisible = 4
};

// Particles are packed in blocks so that splashes and aggregates can be written in parallel, each block at an
// offset found by a prefix sum of the blocks' counts.
constexpr std::size_t kPackBlockSize = 16384;

// How far a splash's blob may reach, in Mantaflow kernel radii: a lone drop's is one; a few neighbours on one
// side stretch it a little; more than this is a body, whose surface the aggregates draw.
constexpr float kMaxBlobPerKernel = 1.25f;

}  // namespace

LiquidCandidates selectLiquidCandidates(const Particles& particles, const Camera& camera,
                                        const LiquidParameters& parameters, const SolidDepthTiles* solids) {
  const ViewFrustum frustum(camera);
  const std::size_t count = particles.size();
  std::vector<std::uint8_t> roles(count, kIneligible);
  const float largestOffset = largestSurfaceOffset(parameters);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& block) {
        for (std::size_t i = block.begin(); i != block.end(); ++i) {
          const float radius = particles.radii[i];
          const glm::vec3& position = particles.positions[i];
          if (particles.kinds[i] != ParticleKind::Liquid || !(radius > 0.0f) || !std::isfinite(radius) ||
              !std::isfinite(position.x + position.y + position.z))
            continue;
          // A drawn instance reaches at most max_ellipsoid_scale r from its centre, grown by its surface
          // offset, which smoothing moves by at most lambda R from the particle; its neighbours lie within
          // R more.
          const float neighbourhood = parameters.neighbour_radius * radius;
          const float drawnReach = (std::max(1.0f, parameters.max_ellipsoid_scale) + largestOffset) * radius +
                                   parameters.anisotropy_smoothing * neighbourhood;
          const glm::vec3 centre = frustum.cameraFromWorld(position);
          // One the solids hide wholly is still a neighbour of those drawn beside it, as one outside the
          // frustum is.
          if (frustum.reachedBySphere(centre, drawnReach))
            roles[i] = solids && solids->hidesSphere(centre, drawnReach) ? kBehindSolids : kVisible;
          else if (frustum.reachedBySphere(centre, drawnReach + neighbourhood))
            roles[i] = kNeighbourOnly;
          else
            roles[i] = kOutside;
        }
      });

  LiquidCandidates candidates;
  std::size_t liquid = 0, selected = 0;
  for (std::size_t i = 0; i < count; ++i) {
    liquid += particles.kinds[i] == ParticleKind::Liquid;
    selected += roles[i] >= kNeighbourOnly;
    candidates.eligible += roles[i] != kIneligible;
    candidates.behindSolids += roles[i] == kBehindSolids;
  }
  ParticleCloud& cloud = candidates.cloud;
  cloud.resize(selected);
  std::size_t next = 0, visible = 0;
  float largestRadius = 0.0f;
  for (std::size_t i = 0; i < count; ++i) {
    if (roles[i] < kNeighbourOnly) continue;
    cloud.x[next] = particles.positions[i].x;
    cloud.y[next] = particles.positions[i].y;
    cloud.z[next] = particles.positions[i].z;
    cloud.radius[next] = particles.radii[i];
    cloud.visible[next] = roles[i] == kVisible;
    visible += roles[i] == kVisible;
    largestRadius = std::max(largestRadius, particles.radii[i]);
    ++next;
  }
  candidates.culled = liquid - visible - candidates.behindSolids;
  candidates.cellSize = selected > 0 ? parameters.neighbour_radius * largestRadius : 1.0f;
  return candidates;
}

void classifyAndPack(const NeighbourGrid& grid, const ParticleShapes& shapes, float restDensity,
                     const LiquidParameters& parameters, MantaflowSurfaceSearch* meshSurface,
                     LiquidPreparation& preparation) {
  const ParticleCloud& cloud = grid.particles();
  const bool split = parameters.layers != "merged";
  const float splashBelow = split ? parameters.splash_density_threshold * restDensity : 0.0f;
  const auto isSplash = [&](std::size_t i) {
    return split && shapes.kinds[i] != ShapeKind::Interior && shapes.densities[i] < splashBelow;
  };

  // With Mantaflow's surface known, each splash is as large as that surface around it; a splash whose blob is
  // empty (the body's surface passes near it) is not drawn.
  std::vector<float> splashRadii;
  if (split && meshSurface) {
    splashRadii.assign(cloud.size(), 0.0f);
    const float maxRadius = kMaxBlobPerKernel * meshSurface->kernelRadius();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cloud.size(), 256),
                      [&](const tbb::blocked_range<std::size_t>& block) {
                        for (std::size_t i = block.begin(); i != block.end(); ++i) {
                          if (shapes.kinds[i] == ShapeKind::Hidden || !isSplash(i)) continue;
                          const glm::vec3 particle(cloud.x[i], cloud.y[i], cloud.z[i]);
                          splashRadii[i] = meshSurface->inscribedRadius(i, particle, maxRadius, 3);
                        }
                      });
  }
  const auto splashRadius = [&](std::size_t i) {
    return splashRadii.empty() ? (1.0f + parameters.surface_offset) * cloud.radius[i] : splashRadii[i];
  };
  const auto absorbed = [&](std::size_t i) {
    return !splashRadii.empty() && isSplash(i) && !(splashRadii[i] > 0.0f);
  };

  const std::size_t blockCount = (cloud.size() + kPackBlockSize - 1) / kPackBlockSize;
  std::vector<std::size_t> splashOffsets(blockCount + 1, 0), aggregateOffsets(blockCount + 1, 0);
  const auto blockRange = [&](std::size_t block) {
    return std::make_pair(block * kPackBlockSize, std::min(cloud.size(), (block + 1) * kPackBlockSize));
  };
  tbb::parallel_for(std::size_t(0), blockCount, [&](std::size_t block) {
    const auto [begin, end] = blockRange(block);
    for (std::size_t i = begin; i < end; ++i) {
      if (shapes.kinds[i] == ShapeKind::Hidden || absorbed(i)) continue;
      ++(isSplash(i) ? splashOffsets : aggregateOffsets)[block + 1];
    }
  });
  for (std::size_t block = 0; block < blockCount; ++block) {
    splashOffsets[block + 1] += splashOffsets[block];
    aggregateOffsets[block + 1] += aggregateOffsets[block];
  }

  preparation.splashes.resize(splashOffsets.back());
  preparation.aggregates.resize(aggregateOffsets.back());
  std::vector<std::size_t> interiorPerBlock(blockCount, 0);
  tbb::parallel_for(std::size_t(0), blockCount, [&](std::size_t block) {
    const auto [begin, end] = blockRange(block);
    std::size_t nextSplash = splashOffsets[block], nextAggregate = aggregateOffsets[block];
    for (std::size_t i = begin; i < end; ++i) {
      if (shapes.kinds[i] == ShapeKind::Hidden || absorbed(i)) continue;
      if (isSplash(i)) {
        preparation.splashes[nextSplash++] =
            sphereInstance(glm::vec3(cloud.x[i], cloud.y[i], cloud.z[i]), splashRadius(i));
      } else {
        preparation.aggregates[nextAggregate++] = shapes.instances[i];
        interiorPerBlock[block] += shapes.kinds[i] == ShapeKind::Interior;
      }
    }
  });
  preparation.isotropicInterior = 0;
  for (std::size_t interior : interiorPerBlock)
    preparation.isotropicInterior += interior;
  preparation.splashesAbsorbed = 0;
  for (std::size_t i = 0; i < cloud.size() && !splashRadii.empty(); ++i)
    preparation.splashesAbsorbed += shapes.kinds[i] != ShapeKind::Hidden && absorbed(i);

  if (parameters.surface != "raymarch") return;
  // The marched density sums every candidate, the neighbours outside the frustum included (their kernels
  // reach into it), each sized as the drawn surface sizes it.
  preparation.marchedAggregates.clear();
  preparation.marchedSplashes.clear();
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const glm::vec3 position(cloud.x[i], cloud.y[i], cloud.z[i]);
    if (shapes.kinds[i] == ShapeKind::Hidden)
      preparation.marchedAggregates.emplace_back(position, parameters.surface_offset * cloud.radius[i]);
    else if (absorbed(i))
      continue;
    else if (isSplash(i))
      preparation.marchedSplashes.emplace_back(position, splashRadius(i));
    else
      preparation.marchedAggregates.emplace_back(position, shapes.offsets[i] * cloud.radius[i]);
  }
}

bool aggregatesContain(const std::vector<EllipsoidInstance>& aggregates, const glm::vec3& point,
                       const DomainBox* domain) {
  if (domain) {
    const glm::vec3 inBox(glm::inverse(domain->worldFromBox) * glm::vec4(point, 1.0f));
    if (glm::any(glm::lessThan(inBox, domain->low)) || glm::any(glm::greaterThan(inBox, domain->high)))
      return false;
  }
  for (const EllipsoidInstance& ellipsoid : aggregates) {
    const glm::vec3 offset = point - glm::vec3(ellipsoid.centreAndBoundingRadius);
    const float bound = ellipsoid.centreAndBoundingRadius.w;
    if (glm::dot(offset, offset) > bound * bound) continue;
    // The rows of the inverse axes matrix map the offset onto the unit sphere.
    const glm::vec3 unit(glm::dot(glm::vec3(ellipsoid.inverseAxesRows[0]), offset),
                         glm::dot(glm::vec3(ellipsoid.inverseAxesRows[1]), offset),
                         glm::dot(glm::vec3(ellipsoid.inverseAxesRows[2]), offset));
    if (glm::dot(unit, unit) <= 1.0f) return true;
  }
  return false;
}

LiquidPreparation prepareLiquid(const Particles& particles, const Camera& camera,
                                const LiquidParameters& parameters, FrameLiquidCache* frameCache,
                                const SolidDepthTiles* solids) {
  const Clock::time_point start = Clock::now();
  LiquidPreparation preparation;
  LiquidCandidates candidates = selectLiquidCandidates(particles, camera, parameters,
                                                       parameters.surface == "raymarch" ? nullptr : solids);
  preparation.culled = candidates.culled;
  preparation.behindSolids = candidates.behindSolids;
  const bool wholeLiquid = candidates.cloud.size() == candidates.eligible;
  const NeighbourGrid grid(std::move(candidates.cloud), candidates.cellSize);
  const Clock::time_point gridBuilt = Clock::now();

  // A view whose candidates are every liquid particle sorts them into the cloud every such view of the frame
  // sorts them into (the same particles, the same cell size): it shares what frameCache remembers of it.
  FrameLiquidCache* shared = frameCache && wholeLiquid ? frameCache : nullptr;
  if (shared && shared->cellSize != grid.cellSize()) {
    shared->search.reset();
    shared->shapes.reset(grid.particles().size());
    shared->cellSize = grid.cellSize();
  }

  // Mantaflow's surface (liquid.mesh_kernel_radius, in radii of the largest particle: a Mantaflow liquid's
  // particles all have one radius) sizes each splash and each surface particle's offset.
  // Its level set and searches depend on the candidates, not on the eye.
  std::optional<MantaflowSurfaceSearch> ownSurface;
  MantaflowSurfaceSearch* meshSurface = nullptr;
  const ParticleCloud& cloud = grid.particles();
  if (parameters.mesh_kernel_radius > 0.0f && cloud.size() > 0) {
    const float kernelRadius =
        parameters.mesh_kernel_radius * *std::max_element(cloud.radius.begin(), cloud.radius.end());
    if (shared && shared->search && shared->search->kernelRadius() == kernelRadius) {
      meshSurface = &*shared->search;
    } else {
      std::optional<MantaflowSurfaceSearch>& built = shared ? shared->search : ownSurface;
      built.emplace(MantaflowLevelSet(cloud, kernelRadius), cloud.size());
      meshSurface = &*built;
    }
  }
  AnisotropySettings settings = AnisotropySettings::fromParameters(parameters);
  // N_epsilon and rho_0 from the whole frame's particles, not the view's, so every view shapes and splits a
  // particle alike.
  if (frameCache && !frameCache->neighbourhood)
    frameCache->neighbourhood = frameNeighbourhood(particles, parameters);
  const FrameNeighbourhood frame =
      frameCache ? *frameCache->neighbourhood : frameNeighbourhood(particles, parameters);
  preparation.fullNeighbours = frame.fullNeighbours;
  preparation.restDensity = frame.restDensity;
  settings.minNeighbours = frame.minNeighbours;
  // A lattice of spacing s holds (4 pi / 3) R^3 / s^3 particles within R of each one, itself included.
  if (cloud.size() > 0)
    preparation.particleSpacing =
        candidates.cellSize * std::cbrt(4.18879f / (preparation.fullNeighbours + 1.0f));
  preparation.minNeighboursApplied = settings.minNeighbours;
  settings.eye = camera.position();
  settings.meshSurface = meshSurface;
  settings.memory = shared ? &shared->shapes : nullptr;
  const ParticleShapes shapes = shapeParticles(grid, settings);
  classifyAndPack(grid, shapes, preparation.restDensity, parameters, settings.meshSurface, preparation);
  const Clock::time_point end = Clock::now();

  preparation.neighbourMilliseconds = millisecondsBetween(start, gridBuilt);
  preparation.anisotropyMilliseconds = millisecondsBetween(gridBuilt, end);
  preparation.totalMilliseconds = millisecondsBetween(start, end);
  return preparation;
}

}  // namespace spindrift
