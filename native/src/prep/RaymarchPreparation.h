#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "prep/LiquidPreparation.h"
#include "spindrift/Camera.h"
#include "spindrift/Parameters.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// The uniform grid of the ray-marched surface (adaptive ray marching paper, 4.1): cells of the largest
/// kernel support h, so every particle that reaches a point lies in the 3x3x3 cells around the point's cell.
/// Each side has an even number of cells, so that 2x2x2 cells pack into one texel of the density mask.
struct RaymarchGrid {
  glm::vec3 origin{0.0f};    ///< World position of the grid's minimum corner.
  float cellSize = 1.0f;     ///< At least h; larger only where the grid would exceed kMaximumCells.
  glm::ivec3 size{2, 2, 2};  ///< Cells per axis, even.
  std::size_t cellCount() const { return std::size_t(size.x) * size.y * size.z; }
  static constexpr std::size_t kMaximumCells = std::size_t(1) << 23;
};

/// The liquid particles whose density can reach the view frustum, for the GPU neighbour grid.
struct RaymarchPreparation {
  std::vector<glm::vec4> particles;  ///< World position; w: the particle's kernel support h_j.
  float particleRadius = 1.0f;       ///< r, the radius the parameters are scaled by.
  float smoothingRadius = 1.0f;      ///< The largest h_j (at least liquid.raymarch_smoothing_radius r).
  RaymarchGrid grid;
  /// A Mantaflow liquid's domain box: the marched surface is clipped to it, as the drawn one is.
  std::optional<DomainBox> domain;
};

/// The grid around particles spanning [low, high] (an empty grid of 2x2x2 cells when low > high).
RaymarchGrid fitRaymarchGrid(const glm::vec3& low, const glm::vec3& high, float smoothingRadius);

/// How far above its top layer of particles the iso-surface of a flat body stands: the density (sum of
/// (1 - q^2)^3, q = d / support) of a half space of particles on a cubic lattice of `spacing`, at the point
/// straight above a top particle, equals `iso` that high.
float flatIsoSurfaceHeight(float support, float spacing, float iso);

/// Sizes each particle's kernel so the marched surface stands where the drawn one does
/// (docs/raymarch.md, "Kernel and iso-value"): an aggregate grown by an offset o gets the support that puts
/// a flat body (Mantaflow's lattice, spacing r / kRadiusPerSpacing) at the drawn flat surface, 0.4 r + o
/// above its top particles, and never less than liquid.raymarch_smoothing_radius r; a splash of radius t the
/// support whose lone iso-surface is a sphere of radius t. Keeps those within the support of the view
/// frustum and fits the grid around them, with one empty cell of margin on every side (so the 3x3x3
/// neighbourhood of any cell a ray meets stays inside the grid). `domain` (may be null): the box to clip to.
RaymarchPreparation prepareRaymarch(const LiquidPreparation& liquid, const Camera& camera,
                                    float particleRadius, const LiquidParameters& parameters,
                                    const DomainBox* domain);

}  // namespace spindrift
