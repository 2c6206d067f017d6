#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "spindrift/FloatImage.h"
#include "spindrift/Particles.h"

namespace spindrift {

/// Triangles in world space: three vertex indices per triangle.
struct TriangleMesh {
  std::vector<glm::vec3> vertices;
  std::vector<glm::uvec3> triangles;

  /// Throws Error, starting with `what`, when an index is out of range or a vertex is not finite.
  void validate(const std::string& what) const;
};

/// What a host application (the Python module, Blender's add-on) hands over in memory for one frame, beside
/// the scene's files. Everything is optional; an empty FrameInputs renders the scene's files alone.
struct FrameInputs {
  /// World space; added to the particles of the scene's sources. Particles with a non-finite position or a
  /// radius that is not finite and positive are dropped and counted, as file loading does.
  Particles particles;
  /// Solid geometry drawn into the depth prepass, beside the scene's `occluders` files: the frame's solid
  /// depth is the nearer of these and the background's depth.
  std::vector<TriangleMesh> occluders;
  /// The liquid's own surface; its depth plays the role of `background.liquid_depth` (replacing the scene's
  /// `liquid_mesh`; the nearer of it and a `liquid_depth` file where both are given).
  std::optional<TriangleMesh> liquidMesh;
  /// RGBA, premultiplied, the camera's size: replaces the colour of the scene's `background.image`.
  std::optional<FloatImage> backgroundColor;
  /// One channel of planar eye depth, the camera's size: replaces the depth of the scene's background files.
  std::optional<FloatImage> backgroundDepth;
};

}  // namespace spindrift
