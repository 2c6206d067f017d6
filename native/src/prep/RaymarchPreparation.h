#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "spindrift/Camera.h"
#include "spindrift/Parameters.h"
#include "spindrift/Particles.h"

namespace spindrift {

/// The uniform grid of the ray-marched surface (adaptive ray marching paper, 4.1): cells of the kernel's
/// support h, so every particle that reaches a point lies in the 3x3x3 cells around the point's cell. Each
/// side has an even number of cells, so that 2x2x2 cells pack into one texel of the density mask.
struct RaymarchGrid {
  glm::vec3 origin{0.0f};    ///< World position of the grid's minimum corner.
  float cellSize = 1.0f;     ///< At least h; larger only where the grid would exceed kMaximumCells.
  glm::ivec3 size{2, 2, 2};  ///< Cells per axis, even.
  std::size_t cellCount() const { return std::size_t(size.x) * size.y * size.z; }
  static constexpr std::size_t kMaximumCells = std::size_t(1) << 23;
};

/// The liquid particles whose density can reach the view frustum, for the GPU neighbour grid.
struct RaymarchPreparation {
  std::vector<glm::vec4> particles;  ///< World position; w: the particle's radius.
  float particleRadius = 1.0f;       ///< r, the radius the parameters are scaled by.
  float smoothingRadius = 1.0f;      ///< h = liquid.raymarch_smoothing_radius * r.
  RaymarchGrid grid;
};

/// The grid around particles spanning [low, high] (an empty grid of 2x2x2 cells when low > high).
RaymarchGrid fitRaymarchGrid(const glm::vec3& low, const glm::vec3& high, float smoothingRadius);

/// Selects the liquid particles within h of the frustum and fits the grid around them, with one empty cell
/// of margin on every side (so the 3x3x3 neighbourhood of any cell a ray meets stays inside the grid).
RaymarchPreparation prepareRaymarch(const Particles& particles, const Camera& camera, float particleRadius,
                                    const LiquidParameters& parameters);

}  // namespace spindrift
