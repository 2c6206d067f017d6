#pragma once

#include <filesystem>

#include "spindrift/FrameInputs.h"

namespace spindrift {

/// Reads a Wavefront OBJ file's vertices (`v x y z`, an optional w ignored) and faces (`f`; polygons are
/// split into fans of triangles; `i`, `i/t`, `i//n`, `i/t/n` and negative, relative indices). Every other
/// statement (normals, texture coordinates, groups, materials) is ignored. Throws Error naming the file and
/// line for a malformed statement or an index outside the vertices read so far.
TriangleMesh readObjMesh(const std::filesystem::path& path);

}  // namespace spindrift
