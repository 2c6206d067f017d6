#pragma once

#include <filesystem>
#include <string>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

// What Blender 3.4's Mantaflow does to turn FLIP particles into the liquid mesh, reduced to the numbers a
// screen-space renderer needs (docs/mantaflow-caches.md, "The liquid mesh").
namespace spindrift {

/// The settings of a Blender liquid domain that shape its mesh, with Blender's defaults. Names follow
/// Blender's Python API (`FluidDomainSettings`).
struct MantaflowDomainSettings {
  float particleRadius = 1.0f;      ///< particle_radius: the simulation's own level set, in cell diagonals.
  float meshParticleRadius = 2.0f;  ///< mesh_particle_radius: the mesh's level set, in half cell diagonals.
  int meshScale = 2;                ///< mesh_scale: the mesh grid is this many times finer (upres).
  int meshSmoothenPos = 1;          ///< mesh_smoothen_pos
  int meshSmoothenNeg = 1;          ///< mesh_smoothen_neg
  float meshConcaveUpper = 3.5f;    ///< mesh_concave_upper
  float meshConcaveLower = 0.4f;    ///< mesh_concave_lower
  int particleNumber = 2;           ///< particle_number: particles seeded per cell along each axis.
  bool improvedMesh = true;         ///< mesh_generator: IMPROVED (true) or UNION.
  float cellSize = 0.0f;            ///< World units; 0 means read it from the cache's config files.
};

/// The header of Mantaflow's `config/config_NNNN.uni` (gzip): what Blender records about the domain.
struct MantaflowCacheConfig {
  glm::ivec3 resolution{0};      ///< Cells along each axis of the simulation grid.
  float normalisedCellSize = 0;  ///< Blender's dx: one cell in units of the domain's longest scaled side.
  glm::vec3 boundsMin{0.0f};     ///< The domain mesh's bounding box, in the object's local frame.
  glm::vec3 boundsMax{0.0f};
  glm::mat4 worldFromObject{1.0f};  ///< The domain object's matrix_world.

  glm::vec3 objectScale() const;
  /// One cubic cell, in world units.
  float cellSize() const;
  /// Maps the cache's particle positions (the simulation grid's frame) to world space: the grid is centred on
  /// the bounding box and one unit is one world unit along each scaled axis (docs/mantaflow-caches.md).
  glm::mat4 worldFromFile() const;
};

/// Reads a config file; throws Error naming the file when it cannot.
MantaflowCacheConfig readMantaflowCacheConfig(const std::filesystem::path& path);

/// The config file beside a Mantaflow particle file pattern (`.../cache/data/fluid_data_####.vdb` or
/// `.../cache/particles/...`): the first `config/config_*.uni` of that cache, or an empty path.
std::filesystem::path findMantaflowCacheConfig(const std::filesystem::path& particlePattern);

/// How far Mantaflow's mesh stands off the particles, and the sizes Spindrift draws to stand where it does.
struct LiquidSurfaceFromDomain {
  float meshKernelRadius = 0;  ///< r_m: Mantaflow's particle radius in its mesh level set, world units.
  float flatOffset = 0;        ///< Mantaflow's surface above the top layer of a flat body, world units.
  float radius = 0;            ///< Spindrift's particle radius r (shapes, neighbourhoods), world units.
  float surfaceOffset = 0;     ///< How far every drawn ellipsoid is grown, world units.
  std::string origin;          ///< One line saying where the numbers came from, for --stats.
};

/// The flat-surface offset of a Mantaflow liquid above its top particle layer, in mesh cells, for a particle
/// radius (mesh cells) and particle spacing (mesh cells): the zero of the averaged (Zhu–Bridson) level set
/// above a lattice of particles filling a half space.
float mantaflowFlatOffset(float kernelRadiusCells, float spacingCells);

/// Spindrift's particle radius per particle spacing: spheres that far apart overlap into a closed surface
/// without bloating thin sheets (the radius the examples used before it was derived, 0.55 cells at 2
/// particles per cell).
constexpr float kRadiusPerSpacing = 1.1f;

/// Spindrift's flat surface of anisotropic ellipsoids stands this many radii above the top particle layer
/// (liquid.md: a particle on a flat free surface is drawn about (r, r, 0.4 r)).
constexpr float kSpindriftFlatOffsetRadii = 0.4f;

LiquidSurfaceFromDomain liquidSurfaceFromDomain(const MantaflowDomainSettings& settings, float cellSize);

}  // namespace spindrift
