#include "prep/SurfaceRelaxation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "prep/FullNeighbourhood.h"

namespace spindrift {
namespace {

constexpr std::size_t kMinLiquid = 64;
constexpr float kMinFullNeighbours = 8.0f;  // fewer: no body to speak of, only spray
constexpr double kFullPercentile = 0.9;  // of the particles' densities: full density, as fullNeighbourCount
constexpr std::size_t kMinFitNeighbours = 8;
// How much a neighbour facing another way counts: exp(-(1 - n_i . n_j) / kFacingScale). Across a box's edge
// (normals 90 degrees apart) exp(-10); five spacings along a sphere 25 spacings across (23 degrees) 0.45.
constexpr double kFacingScale = 0.1;
constexpr int kOuterWeightPower = 4;  // (1 - density)^4: the outermost particles hold the surface

std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  // 21 bits per axis: a frame spanning two million cells per axis merges far cells into one bucket, which
  // only costs distance checks.
  const auto part = [](std::int64_t v) { return std::uint64_t(v + (1 << 20)) & 0x1FFFFF; };
  return (part(x) << 42) | (part(y) << 21) | part(z);
}

// Positions sorted by cube cells of side `cell`, as arrays the distance loops read in order; `index` maps a
// sorted place back to the particle.
struct SortedCells {
  float cell = 0.0f;
  std::vector<float> x, y, z;
  std::vector<std::uint32_t> index;
  std::vector<std::uint32_t> cellStart;  // each occupied cell's first sorted place; then the end
  std::vector<std::int64_t> cellX, cellY, cellZ;
  std::unordered_map<std::uint64_t, std::uint32_t> cellOf;

  std::int64_t coordinate(float v) const { return std::int64_t(std::floor(double(v) / double(cell))); }
};

SortedCells sortByCell(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& which,
                       float cell) {
  SortedCells sorted;
  sorted.cell = cell;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  keyed.reserve(which.size());
  for (std::uint32_t i : which) {
    const glm::vec3& p = positions[i];
    keyed.emplace_back(cellKey(sorted.coordinate(p.x), sorted.coordinate(p.y), sorted.coordinate(p.z)), i);
  }
  std::sort(keyed.begin(), keyed.end());
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    const glm::vec3& p = positions[keyed[k].second];
    if (k == 0 || keyed[k].first != keyed[k - 1].first) {
      sorted.cellOf.emplace(keyed[k].first, std::uint32_t(sorted.cellStart.size()));
      sorted.cellStart.push_back(std::uint32_t(k));
      sorted.cellX.push_back(sorted.coordinate(p.x));
      sorted.cellY.push_back(sorted.coordinate(p.y));
      sorted.cellZ.push_back(sorted.coordinate(p.z));
    }
    sorted.x.push_back(p.x);
    sorted.y.push_back(p.y);
    sorted.z.push_back(p.z);
    sorted.index.push_back(keyed[k].second);
  }
  sorted.cellStart.push_back(std::uint32_t(keyed.size()));
  return sorted;
}

using Ranges = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// The sorted ranges of the cells within `reach` cells of cell `cell`.
void rangesNear(const SortedCells& cells, std::size_t cell, int reach, Ranges& ranges) {
  ranges.clear();
  const std::int64_t cx = cells.cellX[cell], cy = cells.cellY[cell], cz = cells.cellZ[cell];
  for (std::int64_t dx = -reach; dx <= reach; ++dx)
    for (std::int64_t dy = -reach; dy <= reach; ++dy)
      for (std::int64_t dz = -reach; dz <= reach; ++dz) {
        const auto found = cells.cellOf.find(cellKey(cx + dx, cy + dy, cz + dz));
        if (found == cells.cellOf.end()) continue;
        const std::uint32_t first = cells.cellStart[found->second], last = cells.cellStart[found->second + 1];
        // Cells along z are neighbours in the sorted order: a column is one range, which the vectorised
        // distance loops run through in fewer, longer passes.
        if (!ranges.empty() && ranges.back().second == first)
          ranges.back().second = last;
        else
          ranges.emplace_back(first, last);
      }
}

// The kernel sum phi(x) = sum_j (1 - |x - x_j|^2 / H^2)^3 over the liquid within H, and its gradient, for
// every liquid particle (in `density` and `gradient`, by particle). Cells are H wide: each cell's candidates
// (its 27 cells') are copied together once, and each of its particles runs one vectorised loop over them.
void densities(const SortedCells& liquid, float kernelRadius, std::vector<double>& density,
               std::vector<glm::dvec3>& gradient) {
  const float inverseH2 = 1.0f / (kernelRadius * kernelRadius);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, liquid.cellStart.size() - 1, 4),
                    [&](const tbb::blocked_range<std::size_t>& cells) {
                      Ranges ranges;
                      std::vector<float> nx, ny, nz;
                      for (std::size_t c = cells.begin(); c != cells.end(); ++c) {
                        rangesNear(liquid, c, 1, ranges);
                        nx.clear();
                        ny.clear();
                        nz.clear();
                        for (const auto& [first, last] : ranges) {
                          nx.insert(nx.end(), liquid.x.begin() + first, liquid.x.begin() + last);
                          ny.insert(ny.end(), liquid.y.begin() + first, liquid.y.begin() + last);
                          nz.insert(nz.end(), liquid.z.begin() + first, liquid.z.begin() + last);
                        }
                        const std::size_t count = nx.size();
                        const float *cx = nx.data(), *cy = ny.data(), *cz = nz.data();
                        for (std::uint32_t m = liquid.cellStart[c]; m < liquid.cellStart[c + 1]; ++m) {
                          const float px = liquid.x[m], py = liquid.y[m], pz = liquid.z[m];
                          // Eight lanes of partial sums, which the compiler keeps in vector registers.
                          constexpr std::size_t kLanes = 8;
                          float value[kLanes] = {}, gx[kLanes] = {}, gy[kLanes] = {}, gz[kLanes] = {};
                          const auto add = [&](std::size_t lane, std::size_t k) {
                            const float dx = px - cx[k], dy = py - cy[k], dz = pz - cz[k];
                            const float t = std::max(1.0f - (dx * dx + dy * dy + dz * dz) * inverseH2, 0.0f);
                            const float t2 = t * t;
                            value[lane] += t2 * t;
                            gx[lane] += t2 * dx;
                            gy[lane] += t2 * dy;
                            gz[lane] += t2 * dz;
                          };
                          std::size_t k = 0;
                          for (; k + kLanes <= count; k += kLanes)
                            for (std::size_t lane = 0; lane < kLanes; ++lane)
                              add(lane, k + lane);
                          for (std::size_t lane = 0; k < count; ++k, ++lane)
                            add(lane, k);
                          float sumValue = 0.0f, sumX = 0.0f, sumY = 0.0f, sumZ = 0.0f;
                          for (std::size_t lane = 0; lane < kLanes; ++lane) {
                            sumValue += value[lane];
                            sumX += gx[lane];
                            sumY += gy[lane];
                            sumZ += gz[lane];
                          }
                          const std::uint32_t i = liquid.index[m];
                          density[i] = sumValue;
                          gradient[i] = (-6.0 * double(inverseH2)) * glm::dvec3(sumX, sumY, sumZ);
                        }
                      }
                    });
}

// How far a particle must rise along `direction` to reach the algebraic sphere fitted through its surface
// neighbours (Guennebaud and Gross 2007, equations 11-13, about the particle): zero or less where it lies on
// or above it, or where the fit does not hold.
struct Rise {
  double distance = 0.0;
  glm::dvec3 direction{0.0};
};

// The fit's weighted sums over the neighbours, positions taken about the particle.
struct FitSums {
  double w = 0.0, pn = 0.0, pp = 0.0;
  glm::dvec3 p{0.0}, n{0.0};
  std::size_t count = 0;
};

Rise sphereRise(const FitSums& sums, const glm::dvec3& own, float fitRadius) {
  Rise rise;
  const double rho2 = double(fitRadius) * fitRadius;
  if (sums.count < kMinFitNeighbours || !(sums.w > 0.0)) return rise;
  const double spread = sums.pp - glm::dot(sums.p, sums.p) / sums.w;
  if (!(spread > 1e-12 * rho2 * sums.w)) return rise;
  // s(x) = u0 + u . x + u4 |x|^2, positive outside (its gradient follows the outward normals).
  const double u4 = 0.5 * (sums.pn - glm::dot(sums.p, sums.n) / sums.w) / spread;
  const glm::dvec3 u = (sums.n - 2.0 * u4 * sums.p) / sums.w;
  const double u0 = -(glm::dot(u, sums.p) + u4 * sums.pp) / sums.w;
  const double uLength = glm::length(u);
  if (!(uLength > 0.0)) return rise;
  double outside;  // the particle's signed distance from the surface, positive outside
  glm::dvec3 outward;
  // A sphere whose centre lies a thousand fit radii away is a plane to double precision's comfort.
  if (std::abs(u4) * 2.0e3 * fitRadius < uLength) {
    outside = u0 / uLength;
    outward = u / uLength;
  } else {
    const glm::dvec3 centre = -u / (2.0 * u4);
    const double radius2 = glm::dot(centre, centre) - u0 / u4;
    const double fromCentre = glm::length(centre);
    if (!(radius2 > 0.0) || !(fromCentre > 0.0)) return rise;
    const double sign = u4 > 0.0 ? 1.0 : -1.0;  // a convex patch (liquid inside the sphere) or a concave one
    outside = sign * (fromCentre - std::sqrt(radius2));
    outward = sign * (-centre / fromCentre);
  }
  if (!std::isfinite(outside) || !(glm::dot(outward, own) > 0.0)) return rise;
  rise.distance = -outside;
  rise.direction = outward;
  return rise;
}

// The rise of every surface particle (sorted places of `surface`), from the neighbours within fitRadius,
// weighted (1 - d^2 / rho^2)^4 (1 - phi_j)^4 exp(-(1 - n_i . n_j) / kFacingScale).
void surfaceRises(const SortedCells& surface, const std::vector<glm::dvec3>& normals,
                  const std::vector<double>& density, float fitRadius, std::vector<Rise>& rises) {
  const float rho2 = fitRadius * fitRadius, inverseRho2 = 1.0f / rho2;
  const int reach = int(std::ceil(fitRadius / surface.cell));
  // Each neighbour's outer weight and normal, by sorted place.
  std::vector<float> outer(surface.index.size());
  std::vector<glm::vec3> normal(surface.index.size());
  for (std::size_t k = 0; k < surface.index.size(); ++k) {
    const double fall = std::max(1.0 - density[surface.index[k]], 0.0);
    outer[k] = float(fall * fall * fall * fall);
    normal[k] = glm::vec3(normals[surface.index[k]]);
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, surface.cellStart.size() - 1, 2),
                    [&](const tbb::blocked_range<std::size_t>& cells) {
                      Ranges ranges;
                      for (std::size_t c = cells.begin(); c != cells.end(); ++c) {
                        rangesNear(surface, c, reach, ranges);
                        for (std::uint32_t m = surface.cellStart[c]; m < surface.cellStart[c + 1]; ++m) {
                          const glm::vec3 own = normal[m];
                          FitSums sums;
                          for (const auto& [first, last] : ranges)
                            for (std::uint32_t k = first; k < last; ++k) {
                              const glm::vec3 p(surface.x[k] - surface.x[m], surface.y[k] - surface.y[m],
                                                surface.z[k] - surface.z[m]);
                              const float distance2 = glm::dot(p, p);
                              const float facing = glm::dot(own, normal[k]);
                              // Below a cosine of 0.5 the weight is under exp(-5): left out.
                              if (distance2 >= rho2 || facing < 0.5f || !(outer[k] > 0.0f)) continue;
                              const float falloff = 1.0f - distance2 * inverseRho2;
                              const float f2 = falloff * falloff;
                              const double w = double(f2 * f2 * outer[k] *
                                                      std::exp(-(1.0f - facing) * float(1.0 / kFacingScale)));
                              const glm::dvec3 pd(p), nd(normal[k]);
                              ++sums.count;
                              sums.w += w;
                              sums.p += w * pd;
                              sums.n += w * nd;
                              sums.pn += w * glm::dot(pd, nd);
                              sums.pp += w * double(distance2);
                            }
                          rises[m] = sphereRise(sums, glm::dvec3(own), fitRadius);
                        }
                      }
                    });
}

}  // namespace

bool relaxesSurface(const LiquidParameters& parameters) {
  return parameters.relax_surface && !(parameters.mesh_kernel_radius > 0.0f);
}

Particles relaxLiquidSurface(const Particles& particles, const LiquidParameters& parameters,
                             SurfaceRelaxationStats& stats) {
  const auto start = std::chrono::steady_clock::now();
  stats = SurfaceRelaxationStats{};
  Particles relaxed = particles;
  const auto finish = [&](std::string why) {
    stats.notApplied = std::move(why);
    stats.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return relaxed;
  };
  std::vector<std::uint32_t> liquid;
  std::vector<float> radii;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (particles.kinds[i] == ParticleKind::Liquid) {
      liquid.push_back(std::uint32_t(i));
      radii.push_back(particles.radii[i]);
    }
  if (liquid.size() < kMinLiquid) return finish("fewer than 64 liquid particles");
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  const float neighbourRadius = parameters.neighbour_radius * radii[radii.size() / 2];
  const float fullNeighbours = fullNeighbourCount(particles, parameters.neighbour_radius);
  if (!(fullNeighbours >= kMinFullNeighbours))
    return finish("no body: a particle has " + std::to_string(int(fullNeighbours)) +
                  " neighbours within liquid.neighbour_radius at most");
  // A lattice of spacing s holds (4 pi / 3) R^3 / s^3 particles within R of each one, itself included.
  const float spacing = neighbourRadius * std::cbrt(4.18879f / (fullNeighbours + 1.0f));
  stats.spacing = spacing;
  const float kernelRadius = kKernelRadiusSpacings * spacing;
  const float fitRadius = kFitRadiusSpacings * spacing;

  const std::vector<glm::vec3>& positions = particles.positions;
  const SortedCells sortedLiquid = sortByCell(positions, liquid, kernelRadius);
  std::vector<double> density(particles.size(), 1.0);
  std::vector<glm::dvec3> normals(particles.size(), glm::dvec3(0.0));
  densities(sortedLiquid, kernelRadius, density, normals);
  std::vector<double> sorted;
  sorted.reserve(liquid.size());
  for (std::uint32_t i : liquid)
    sorted.push_back(density[i]);
  const std::size_t fullAt = std::size_t(kFullPercentile * double(sorted.size() - 1));
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(fullAt), sorted.end());
  const double full = sorted[fullAt];
  if (!(full > 0.0)) return finish("no full density");

  std::vector<std::uint32_t> surface;
  for (std::uint32_t i : liquid) {
    density[i] /= full;
    const double gradientLength = glm::length(normals[i]);
    // The density falls outwards: its gradient points in.
    normals[i] = gradientLength > 0.0 ? -normals[i] / gradientLength : glm::dvec3(0.0);
    if (density[i] < kSurfaceDensity && gradientLength > 0.0) surface.push_back(i);
  }
  stats.surfaceParticles = surface.size();
  const SortedCells sortedSurface = sortByCell(positions, surface, 0.5f * fitRadius);
  std::vector<Rise> rises(surface.size());
  surfaceRises(sortedSurface, normals, density, fitRadius, rises);
  // Every rise is computed from the given positions, then applied: the result does not depend on the order.
  const double highest = double(kMaxRaiseSpacings * spacing);
  for (std::size_t m = 0; m < rises.size(); ++m)
    if (rises[m].distance > 0.0) {
      glm::vec3& position = relaxed.positions[sortedSurface.index[m]];
      const glm::vec3 before = position;
      position += glm::vec3(std::min(rises[m].distance, highest) * rises[m].direction);
      stats.raised += position != before;
    }
  return finish("");
}

const Particles& SurfaceRelaxationAcrossFrames::forFrame(const Particles& given,
                                                         const LiquidParameters& parameters,
                                                         SurfaceRelaxationStats& stats) {
  if (!relaxesSurface(parameters)) {
    stats = SurfaceRelaxationStats{};
    stats.notApplied = parameters.relax_surface ? "Mantaflow's surface (liquid.mesh_kernel_radius)"
                                                : "liquid.relax_surface is off";
    keyed_ = false;
    return given;
  }
  const auto start = std::chrono::steady_clock::now();
  if (parameters.reuse_shapes && keyed_ && parameters.neighbour_radius == neighbourRadius_ &&
      given.positions == given_.positions && given.radii == given_.radii && given.kinds == given_.kinds) {
    stats = stats_;
    stats.kept = true;
    stats.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return relaxed_;
  }
  relaxed_ = relaxLiquidSurface(given, parameters, stats_);
  keyed_ = parameters.reuse_shapes;
  if (keyed_) {
    given_ = given;
    neighbourRadius_ = parameters.neighbour_radius;
  }
  stats = stats_;
  return relaxed_;
}

}  // namespace spindrift
