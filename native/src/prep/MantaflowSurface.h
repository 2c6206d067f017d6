#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "prep/NeighbourGrid.h"

namespace spindrift {

/// Mantaflow's averaged (Zhu–Bridson) particle level set φ(x) = |x − x̄(x)| − r_m, x̄ the mean of the liquid
/// particles within 2 r_m of x weighted by max(0, 1 − d²/(2 r_m)²) (docs/mantaflow-caches.md), over a cloud
/// whose particles are lumped per cell of r_m / 2 of a dense grid: each cell counts as its particles at their
/// centroid. A sum over the 2 r_m ball then reads a few hundred cells in contiguous runs instead of about
/// 1,400 particles; the tests bound what the lumping moves the surface. The concavity correction (c ≤ 1) and
/// the mesh smoothing are left out: both only matter where the surface is concave or curved within a few
/// cells.
class MantaflowLevelSet {
 public:
  MantaflowLevelSet(const ParticleCloud& cloud, float kernelRadius);

  float kernelRadius() const { return kernelRadius_; }

  MantaflowLevelSet(MantaflowLevelSet&&) = default;

  /// x̄(at) − at; false (and 0) when no particle lies within 2 r_m.
  bool offsetToMean(const glm::vec3& at, glm::vec3& offset) const;

  /// x̄(at) − at interpolated trilinearly between its values at the corners of `at`'s cell of a lattice of
  /// r_m / 2 fixed in the world, as Mantaflow samples φ on its mesh grid before it meshes it. Each corner's
  /// sum is made once, on first use (safe from several threads, and the same whichever thread makes it):
  /// the searches of a frame touch about a third as many corners as they make queries. Where some corners
  /// have no particle within 2 r_m and others do (the far fringe of the liquid, a kernel radius outside its
  /// surface), and on a level set whose cells had to be coarsened, it is offsetToMean itself.
  bool sampledOffsetToMean(const glm::vec3& at, glm::vec3& offset) const;

  /// How far Mantaflow's mesh reaches out from a particle at `particle`, in world units: 0 when the particle
  /// lies outside the surface (its neighbours pull x̄ more than r_m away: Mantaflow draws no bump for it, the
  /// body's surface passes near it), else the distance to φ = 0 along `out`, the direction away from
  /// x̄(particle), at most `maxRadius`. A lone particle gets r_m. Found by secant steps (`refinements` after
  /// the first guess, each one more sum).
  float surfaceDistance(const glm::vec3& particle, float maxRadius, int refinements, glm::vec3& out) const;

  /// The radius of the largest sphere about a particle at `particle` that Mantaflow's surface holds: the
  /// least of surfaceDistance's reaches along 26 directions (a cube's faces, edges and corners, turned so
  /// that a face looks along `out`), so never more than surfaceDistance. 0 when the particle lies outside the
  /// surface; a lone particle gets r_m.
  float inscribedRadius(const glm::vec3& particle, float maxRadius, int refinements) const;

 private:
  /// The unit direction away from x̄ (`towardsMean` = x̄ − particle, `pull` its length).
  glm::vec3 outwardFrom(const glm::vec3& towardsMean, float pull) const;
  /// How far φ = 0 lies from `particle` along the unit `direction`, at most `maxRadius`, for a particle
  /// whose x̄ lies `pull` from it (less than r_m).
  float reachAlong(const glm::vec3& particle, float pull, const glm::vec3& direction, float maxRadius,
                   int refinements) const;

  float kernelRadius_;
  float cellSize_;
  glm::vec3 origin_{0.0f};
  int cellCounts_[3] = {0, 0, 0};
  // Per cell, z fastest, one array per component: the centroid's x, y and z and the particle count (0 where
  // empty), padded at the end so that a lattice node's stencil loads a run of 16 cells from any cell.
  std::vector<float> cellX_, cellY_, cellZ_, cellCount_;
  // Per column (x, y), the first and last occupied cell along z (first > last where empty): a sum reads only
  // that part of the ball's chord, the empty cells adding nothing.
  std::vector<std::int32_t> occupiedLow_, occupiedHigh_;
  // The lattice of sampledOffsetToMean, z fastest: node n lies at nodeSpacing_ (nodeLow_ + n) in the world
  // and covers the cloud's box grown by 2 r_m (outside it no particle is near). Per node x̄ − x and 1 where
  // some particle is near (else 0); its state is 0 (not summed), 1 (being summed) or 2 (summed). Written
  // through these pointers by the const searches. Empty where the cells were coarsened.
  using Float4 = float __attribute__((vector_size(16)));
  float nodeSpacing_ = 0.0f;
  glm::ivec3 nodeLow_{0}, nodeCounts_{0};
  std::unique_ptr<Float4[]> nodes_;
  std::unique_ptr<std::atomic<std::uint8_t>[]> nodeStates_;
  Float4 nodeOffset(const glm::ivec3& node) const;
};

/// A level set with each particle's searches remembered, so that the views of one frame (the camera's and
/// every light's) search each particle once. Indexed like the cloud the level set was built over; a search is
/// reused only when it was made for the same position, maximum radius and refinements, so a reused result is
/// bit for bit the one a new search would give. One thread at a time may search a given index.
class MantaflowSurfaceSearch {
 public:
  MantaflowSurfaceSearch(MantaflowLevelSet levelSet, std::size_t particles);

  const MantaflowLevelSet& levelSet() const { return levelSet_; }
  float kernelRadius() const { return levelSet_.kernelRadius(); }

  /// MantaflowLevelSet::surfaceDistance for particle `index` at `particle`, remembered: a surface particle's
  /// offset (Anisotropy.cpp).
  float surfaceDistance(std::size_t index, const glm::vec3& particle, float maxRadius, int refinements,
                        glm::vec3& out);

  /// MantaflowLevelSet::inscribedRadius for particle `index` at `particle`, remembered: a splash's size
  /// (classifyAndPack). Kept apart from the offsets: a splash's search (its inscribed blob) is not a surface
  /// particle's.
  float inscribedRadius(std::size_t index, const glm::vec3& particle, float maxRadius, int refinements);

 private:
  struct Search {
    glm::vec3 particle{0.0f};
    float maxRadius = -1.0f;  // Negative: not searched yet.
    int refinements = 0;
    float distance = 0.0f;
    glm::vec3 out{0.0f};
    bool madeFor(const glm::vec3& at, float radius, int steps) const {
      return maxRadius == radius && refinements == steps && particle == at;
    }
  };
  MantaflowLevelSet levelSet_;
  std::vector<Search> offsetSearches_, splashSearches_;
};

}  // namespace spindrift
