#include "prep/Anisotropy.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "prep/MantaflowSurface.h"
#include "prep/NeighbourOffsets.h"
#include "prep/SymmetricEigen.h"

namespace spindrift {
namespace {

// The interior test (see docs/liquid.md, "Particle preparation"). A particle whose neighbours' weighted mean
// lies within 0.1 R of it, whose covariance is within 25% of isotropic and fills at least half of a full
// neighbourhood's spread has neighbours on every side for at least R: its ellipsoid would be a near-sphere
// of about r hidden behind the surface particles, so it is drawn as that sphere without an
// eigen-decomposition.
constexpr float kInteriorMaxOffset = 0.1f;
constexpr float kInteriorMaxAnisotropy = 0.25f;
constexpr float kInteriorMinSpread = 0.5f * kRestCovariance;
// Below this largest eigenvalue (in R^2) the neighbours all but coincide and have no principal directions.
constexpr float kDegenerateCovariance = 1e-6f;

bool isInterior(const glm::vec3& meanOffset, const float covariance[3][3]) {
  if (glm::dot(meanOffset, meanOffset) > kInteriorMaxOffset * kInteriorMaxOffset) return false;
  const float average = (covariance[0][0] + covariance[1][1] + covariance[2][2]) / 3.0f;
  if (!(average >= kInteriorMinSpread)) return false;
  // Gershgorin: every eigenvalue lies within one of these discs, so all lie within 25% of the average.
  for (int row = 0; row < 3; ++row) {
    float discRadius = std::abs(covariance[row][row] - average);
    for (int column = 0; column < 3; ++column)
      if (column != row) discRadius += std::abs(covariance[row][column]);
    if (discRadius > kInteriorMaxAnisotropy * average) return false;
  }
  return true;
}

// The hot loop of the preparation. It is branch-free and its sums are declared reductions, so the compiler
// vectorises it without -ffast-math (-fopenmp-simd, no OpenMP runtime). Every offset lies within R (`inside`
// repeats the gathering's test on the same numbers, so that no rounding can let one past it).
NeighbourMoments accumulateMoments(const NeighbourOffsets& neighbours, float inverseRadius) {
  const float* xs = neighbours.x();
  const float* ys = neighbours.y();
  const float* zs = neighbours.z();
  const int length = neighbours.count();
  float weightSum = 0, mx = 0, my = 0, mz = 0, xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0, kernelSum = 0;
  int count = 0;
#pragma omp simd reduction(+ : weightSum, mx, my, mz, xx, xy, xz, yy, yz, zz, kernelSum, count)
  for (int j = 0; j < length; ++j) {
    const float qx = xs[j] * inverseRadius;
    const float qy = ys[j] * inverseRadius;
    const float qz = zs[j] * inverseRadius;
    const float q2 = qx * qx + qy * qy + qz * qz;
    const bool inside = q2 < 1.0f;
    const float weight = inside ? 1.0f - q2 * std::sqrt(q2) : 0.0f;
    const float falloff = inside ? 1.0f - q2 : 0.0f;
    weightSum += weight;
    mx += weight * qx;
    my += weight * qy;
    mz += weight * qz;
    xx += weight * qx * qx;
    xy += weight * qx * qy;
    xz += weight * qx * qz;
    yy += weight * qy * qy;
    yz += weight * qy * qz;
    zz += weight * qz * qz;
    kernelSum += falloff * falloff * falloff;
    count += inside;
  }
  NeighbourMoments sums;
  sums.weightSum = weightSum;
  sums.weightedOffset = glm::vec3(mx, my, mz);
  sums.xx = xx, sums.xy = xy, sums.xz = xz, sums.yy = yy, sums.yz = yz, sums.zz = zz;
  sums.isotropicKernelSum = kernelSum;
  sums.neighbourCount = std::max(count - 1, 0);
  return sums;
}

// sum_j P(|G (x_j - x_i)|) for the anisotropic kernel G = diag(1 / kernel semi-axes) R^T; vectorised like
// accumulateMoments. The kernel's support lies inside the ball of radius R, so the neighbours within it are
// all it needs.
float anisotropicKernelSum(const NeighbourOffsets& neighbours, const ParticleShape& shape) {
  const glm::vec3 a = shape.axes[0] / shape.kernelSemiAxes[0];
  const glm::vec3 b = shape.axes[1] / shape.kernelSemiAxes[1];
  const glm::vec3 c = shape.axes[2] / shape.kernelSemiAxes[2];
  const float* xs = neighbours.x();
  const float* ys = neighbours.y();
  const float* zs = neighbours.z();
  const int length = neighbours.count();
  float sum = 0.0f;
#pragma omp simd reduction(+ : sum)
  for (int j = 0; j < length; ++j) {
    const float dx = xs[j], dy = ys[j], dz = zs[j];
    const float u = a.x * dx + a.y * dy + a.z * dz;
    const float v = b.x * dx + b.y * dy + b.z * dz;
    const float w = c.x * dx + c.y * dy + c.z * dz;
    const float falloff = std::max(0.0f, 1.0f - (u * u + v * v + w * w));
    sum += falloff * falloff * falloff;
  }
  return sum;
}

// Whether particle i's outward side (away from its neighbours' weighted mean) faces the eye, or no eye is
// set.
bool facesEye(const ParticleCloud& cloud, std::size_t i, const glm::vec3& weightedOffset,
              const AnisotropySettings& settings) {
  if (!settings.eye) return true;
  const glm::vec3 toEye = *settings.eye - glm::vec3(cloud.x[i], cloud.y[i], cloud.z[i]);
  // Silhouette particles face sideways and the 2.5 r neighbourhood's mean tilts either way: only a clearly
  // averted side (more than 120 degrees from the eye) is skipped.
  const float along = -glm::dot(weightedOffset, toEye);
  return along >= -0.5f * glm::length(weightedOffset) * glm::length(toEye);
}

// Particle i's shape and density from its neighbours in `ranges`.
ViewlessShape shapeFromNeighbours(const ParticleCloud& cloud, std::uint32_t i, const IndexRange* ranges,
                                  int rangeCount, const AnisotropySettings& settings,
                                  NeighbourOffsets& neighbours) {
  const float radius = cloud.radius[i];
  const float neighbourhood = settings.neighbourRadius * radius;
  neighbours.gather(cloud, i, 1.0f / neighbourhood, ranges, rangeCount);
  const NeighbourMoments moments = accumulateMoments(neighbours, 1.0f / neighbourhood);
  ViewlessShape result;
  result.shape = shapeFromMoments(moments, radius, settings);
  result.weightedOffset = moments.weightedOffset;
  if (!settings.needDensity) return result;
  // Unit-free density: the kernel's normalisation over its support volume, times r^3.
  if (result.shape.kind == ShapeKind::Anisotropic) {
    const glm::vec3 support = result.shape.kernelSemiAxes / radius;
    const float sum = anisotropicKernelSum(neighbours, result.shape);
    result.density = kKernelNormalisation * sum / (support.x * support.y * support.z);
  } else {
    const float radiusCubed = settings.neighbourRadius * settings.neighbourRadius * settings.neighbourRadius;
    result.density = kKernelNormalisation * moments.isotropicKernelSum / radiusCubed;
  }
  return result;
}

// The offset (in radii) that makes particle i's ellipsoid reach Mantaflow's surface along the particle's
// outward direction: the support of the grown ellipsoid along that direction, from its centre, is the
// distance to the surface; solved for the offset s from sum_k (e_k + s)^2 c_k = T^2 with c_k the squared
// cosines to the axes (sum 1). Clamped to [0, kMeshOffsetPerFlat surfaceOffset].
float offsetToMantaflowSurface(const NeighbourGrid& grid, std::size_t i, const ParticleShape& shape,
                               const glm::vec3& centre, const AnisotropySettings& settings) {
  const ParticleCloud& cloud = grid.particles();
  const float radius = cloud.radius[i];
  const glm::vec3 particle(cloud.x[i], cloud.y[i], cloud.z[i]);
  glm::vec3 out;
  // The surface is searched no farther than the ellipsoid's bounding sphere grown by the flat offset reaches
  // (plus the smoothing's shift of its centre): no aggregate stands out farther along its outward direction
  // than the uniformly grown one could.
  const float longest = std::max({shape.semiAxes.x, shape.semiAxes.y, shape.semiAxes.z});
  const float farthest = longest + settings.surfaceOffset * radius + glm::length(centre - particle);
  const float reach = settings.meshSurface->surfaceDistance(i, particle, farthest, 0, out);
  if (!(reach > 0.0f)) return 0.0f;
  const float target = (reach - glm::dot(centre - particle, out)) / radius;
  if (!(target > 0.0f)) return 0.0f;
  float e = 0.0f, e2 = 0.0f;
  for (int k = 0; k < 3; ++k) {
    const float c = glm::dot(shape.axes[k], out) * glm::dot(shape.axes[k], out);
    const float semi = shape.semiAxes[k] / radius;
    e += semi * c;
    e2 += semi * semi * c;
  }
  const float discriminant = e * e - e2 + target * target;
  const float offset = discriminant > 0.0f ? -e + std::sqrt(discriminant) : 0.0f;
  return std::clamp(offset, 0.0f, kMeshOffsetPerFlat * settings.surfaceOffset);
}

}  // namespace

float reachRadiusOffset(const ParticleShape& shape, float radius) {
  const float shortest = std::min(shape.semiAxes.x, std::min(shape.semiAxes.y, shape.semiAxes.z));
  return std::max(1.0f - shortest / radius, 0.0f);
}

float largestSurfaceOffset(const LiquidParameters& parameters) {
  // The shortest semi-axis is at least 1 / k_r of the longest, which is at least k_n r.
  const float reach =
      parameters.reach_radius && !(parameters.mesh_kernel_radius > 0.0f)
          ? 1.0f - parameters.anisotropy_isotropic_scale / std::max(parameters.anisotropy_max_ratio, 1.0f)
          : 0.0f;
  const float meshOffset =
      parameters.mesh_kernel_radius > 0.0f ? kMeshOffsetPerFlat * parameters.surface_offset : 0.0f;
  return std::max({parameters.surface_offset, reach, meshOffset});
}

AnisotropySettings AnisotropySettings::fromParameters(const LiquidParameters& parameters) {
  AnisotropySettings settings;
  settings.neighbourRadius = parameters.neighbour_radius;
  settings.maxRatio = parameters.anisotropy_max_ratio;
  settings.minNeighbours = float(parameters.anisotropy_min_neighbours);
  settings.isotropicScale = parameters.anisotropy_isotropic_scale;
  settings.smoothing = parameters.anisotropy_smoothing;
  settings.maxEllipsoidScale = parameters.max_ellipsoid_scale;
  settings.surfaceOffset = parameters.surface_offset;
  settings.reachRadius = parameters.reach_radius;
  settings.needDensity = parameters.layers != "merged";
  return settings;
}

ParticleShape shapeFromMoments(const NeighbourMoments& moments, float radius,
                               const AnisotropySettings& settings) {
  const float neighbourhood = settings.neighbourRadius * radius;
  ParticleShape shape;
  shape.semiAxes = glm::vec3(settings.isotropicScale * radius);
  shape.kernelSemiAxes = glm::vec3(neighbourhood);
  // The particle's own weight (1) keeps weightSum positive.
  const glm::vec3 meanOffset = moments.weightedOffset / moments.weightSum;
  shape.centreOffset = settings.smoothing * neighbourhood * meanOffset;
  if (float(moments.neighbourCount) < settings.minNeighbours) return shape;

  const float inverseWeight = 1.0f / moments.weightSum;
  const glm::vec3& m = meanOffset;
  const float xx = moments.xx * inverseWeight - m.x * m.x, xy = moments.xy * inverseWeight - m.x * m.y;
  const float xz = moments.xz * inverseWeight - m.x * m.z, yy = moments.yy * inverseWeight - m.y * m.y;
  const float yz = moments.yz * inverseWeight - m.y * m.z, zz = moments.zz * inverseWeight - m.z * m.z;
  const float covariance[3][3] = {{xx, xy, xz}, {xy, yy, yz}, {xz, yz, zz}};
  if (isInterior(meanOffset, covariance)) {
    shape.kind = ShapeKind::Interior;
    shape.semiAxes = glm::vec3(radius);
    return shape;
  }

  SymmetricEigen3 eigen;
  if (!symmetricEigen3(xx, xy, xz, yy, yz, zz, eigen)) return shape;
  const glm::dvec3& eigenvalues = eigen.values;
  const double largest = eigenvalues[2];
  if (!(largest > kDegenerateCovariance)) return shape;

  // Yu and Turk's clamp: no eigenvalue below the largest / k_r. Semi-axes are the clamped eigenvalues
  // relative to the rest covariance (the unit-free k_s), so an isotropic neighbourhood at rest gets r.
  glm::vec3 relative;
  for (int k = 0; k < 3; ++k) {
    relative[k] = float(std::max(eigenvalues[k], largest / settings.maxRatio) / kRestCovariance);
    shape.axes[k] = glm::normalize(glm::vec3(eigen.vectors[k]));
  }
  const float longest = float(largest / kRestCovariance);
  // The liquid paper bounds the drawn ellipsoid by maxEllipsoidScale r; k_n r bounds it from below, as it
  // bounds a particle with too few neighbours. The ratio of the axes is kept.
  const float drawnLongest = std::clamp(longest, settings.isotropicScale, settings.maxEllipsoidScale);
  shape.semiAxes = relative * (drawnLongest / longest * radius);
  // The density kernel has the same axes, shrunk if needed to fit the neighbourhood that was searched.
  shape.kernelSemiAxes = relative * (neighbourhood / std::max(1.0f, longest));
  shape.kind = ShapeKind::Anisotropic;
  return shape;
}

EllipsoidInstance ellipsoidInstance(const glm::vec3& centre, const glm::vec3 axes[3],
                                    const glm::vec3& semiAxes) {
  EllipsoidInstance instance;
  const float boundingRadius = std::max(semiAxes.x, std::max(semiAxes.y, semiAxes.z));
  instance.centreAndBoundingRadius = glm::vec4(centre, boundingRadius);
  for (int k = 0; k < 3; ++k)
    instance.inverseAxesRows[k] = glm::vec4(axes[k] / semiAxes[k], 0.0f);
  return instance;
}

EllipsoidInstance sphereInstance(const glm::vec3& centre, float radius) {
  static const glm::vec3 identity[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  return ellipsoidInstance(centre, identity, glm::vec3(radius));
}

const ViewlessShape* ShapeMemory::find(std::size_t index, const glm::vec3& position, float radius) const {
  if (index >= entries_.size()) return nullptr;
  const Entry& entry = entries_[index];
  return entry.radius >= 0.0f && entry.radius == radius && entry.position == position ? &entry.shape
                                                                                      : nullptr;
}

std::size_t ShapeMemory::remembered() const {
  return std::size_t(std::count_if(entries_.begin(), entries_.end(),
                                   [](const Entry& entry) { return entry.radius >= 0.0f; }));
}

void ShapeMemory::remember(std::size_t index, const glm::vec3& position, float radius,
                           const ViewlessShape& shape) {
  if (index >= entries_.size()) return;
  entries_[index] = Entry{position, radius, shape};
}

ParticleShapes shapeParticles(const NeighbourGrid& grid, const AnisotropySettings& settings) {
  const ParticleCloud& cloud = grid.particles();
  ParticleShapes shapes;
  shapes.instances.resize(cloud.size());
  shapes.kinds.assign(cloud.size(), ShapeKind::Hidden);
  shapes.densities.assign(cloud.size(), 0.0f);
  shapes.offsets.assign(cloud.size(), settings.surfaceOffset);

  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, grid.cellCount(), 8),
      [&](const tbb::blocked_range<std::size_t>& cells) {
        IndexRange ranges[9];
        NeighbourOffsets neighbours;
        for (std::size_t cell = cells.begin(); cell != cells.end(); ++cell) {
          const IndexRange members = grid.cellParticles(cell);
          int rangeCount = -1;  // Looked up on the first particle of the cell that is shaped here.
          for (std::uint32_t i = members.begin; i < members.end; ++i) {
            if (!cloud.visible[i]) continue;
            const float radius = cloud.radius[i];
            const glm::vec3 particle(cloud.x[i], cloud.y[i], cloud.z[i]);
            const ViewlessShape* remembered =
                settings.memory ? settings.memory->find(i, particle, radius) : nullptr;
            ViewlessShape computed;
            if (!remembered) {
              if (rangeCount < 0) rangeCount = grid.neighbourRanges(cell, ranges);
              computed = shapeFromNeighbours(cloud, i, ranges, rangeCount, settings, neighbours);
              if (settings.memory) settings.memory->remember(i, particle, radius, computed);
            }
            const ViewlessShape& viewless = remembered ? *remembered : computed;
            const ParticleShape& shape = viewless.shape;
            const glm::vec3 centre = particle + shape.centreOffset;
            shapes.kinds[i] = shape.kind;
            shapes.densities[i] = viewless.density;
            // The surface offset grows every axis by the same length, so the drawn surface moves out by about
            // that much everywhere (exactly so along the axes) while the shape computed at r stays as it is.
            float offset = settings.surfaceOffset;
            if (settings.meshSurface && shape.kind == ShapeKind::Anisotropic &&
                facesEye(cloud, i, viewless.weightedOffset, settings))
              offset = offsetToMantaflowSurface(grid, i, shape, centre, settings);
            else if (!settings.meshSurface && settings.reachRadius && shape.kind == ShapeKind::Anisotropic)
              offset = std::max(offset, reachRadiusOffset(shape, radius));
            shapes.instances[i] = ellipsoidInstance(centre, shape.axes, shape.semiAxes + offset * radius);
            shapes.offsets[i] = offset;
          }
        }
      });
  return shapes;
}

}  // namespace spindrift
