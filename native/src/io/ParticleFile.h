#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace spindrift {

/// What one particle file holds, in the file's own coordinates. Optional attributes are empty when the file
/// has none; otherwise they have one entry per position. Nothing is filtered here: non-finite values are
/// dropped, and counted, when the scene brings particles to world space.
struct ParticleFileData {
  std::vector<glm::vec3> positions;
  std::vector<float> radii;             ///< PLY `radius` or `pscale`; VDB `pscale` if present.
  std::vector<std::int32_t> typeFlags;  ///< Mantaflow `U` (2 spray, 4 bubble, 8 foam) or PLY `type`.
  std::vector<float> life;              ///< Mantaflow `particles_life_secondary` or PLY `life`, in frames.
  std::vector<glm::vec3> velocities;    ///< Mantaflow `particles_velocity*` or PLY `vx vy vz`.
};

/// Reads every point of an OpenVDB PointDataGrid: `gridName`, or the first point grid when empty. Positions
/// are world positions of the grid's transform (`indexToWorld(P + voxel coordinate)`), which for a Mantaflow
/// cache is the domain's local frame with its minimum corner at the origin.
ParticleFileData readVdbPoints(const std::filesystem::path& path, const std::string& gridName);

/// Reads an ASCII or binary (little or big endian) PLY file's `vertex` element: `x y z`, and optionally
/// `radius` or `pscale`, `type`, `life`, `vx vy vz`, in any order, of any PLY scalar type.
ParticleFileData readPly(const std::filesystem::path& path);

/// Chooses the reader by extension (.vdb or .ply); throws Error for anything else.
ParticleFileData readParticleFile(const std::filesystem::path& path, const std::string& gridName);

}  // namespace spindrift
