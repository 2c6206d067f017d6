#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "spindrift/Camera.h"
#include "spindrift/FrameInputs.h"
#include "spindrift/Parameters.h"
#include "spindrift/Particles.h"

namespace spindrift {

enum class ParticleRole { Liquid, Foam };

/// The box a Mantaflow liquid is clipped to: Mantaflow closes its mesh with flat faces just inside the
/// domain's walls (docs/mantaflow-caches.md). `worldFromBox` has unit scale; the box is [low, high] in its
/// frame.
struct DomainBox {
  glm::mat4 worldFromBox{1.0f};
  glm::vec3 low{0.0f};
  glm::vec3 high{0.0f};
};

/// One entry of the scene file's `particles` list. Paths are absolute (resolved against the scene file) and
/// may hold `####`, which stands for the frame number padded with zeros to the number of `#`.
struct ParticleSource {
  std::filesystem::path path;
  std::string grid;  ///< Point grid name in a .vdb; empty means the first point grid.
  ParticleRole role = ParticleRole::Liquid;
  /// For foam sources: every particle of this kind, instead of the per-particle flags of the file.
  std::optional<ParticleKind> kind;
  float radius = 0.05f;  ///< World units; a per-particle radius attribute overrides it.
  /// Where `radius` came from: "scene file", or the Mantaflow domain it was derived from (--stats says it).
  std::string radiusOrigin = "scene file";
  /// For a source with a Mantaflow `domain`: how far Mantaflow's liquid mesh stands off the particles' flat
  /// surface, world units (0 otherwise); it sets liquid.surface_offset (docs/mantaflow-caches.md).
  float meshFlatOffset = 0.0f;
  /// For a source with a Mantaflow `domain`: Mantaflow's mesh kernel radius r_m, world units (0 otherwise);
  /// it sets liquid.mesh_kernel_radius.
  float meshKernelRadius = 0.0f;
  /// For a source with a Mantaflow `domain` whose cache records it: the box its liquid is clipped to.
  std::optional<DomainBox> domainBox;
  glm::mat4 worldFromFile{1.0f};
};

/// A triangle mesh file (Wavefront OBJ) of the scene file's `occluders` or `liquid_mesh`. The path is
/// absolute and may hold `####` like particle paths.
struct MeshSource {
  std::filesystem::path path;
  glm::mat4 worldFromFile{1.0f};
};

/// What lies behind the liquid. Paths are absolute or empty, and may hold `####` like particle paths.
struct Background {
  std::filesystem::path image;  ///< Colour, or empty.
  std::filesystem::path depth;  ///< Planar eye depth; empty means the image's own depth channel, if any.
  bool depthExplicit = false;   ///< True when the scene named `depth`, which must then be found.
  /// Planar eye depth of a render that includes the liquid (foam over a full render); empty when none.
  std::filesystem::path liquidDepth;
  std::filesystem::path environment;  ///< Equirectangular, +Z up as Blender's world; or empty.
  glm::vec3 color{0.05f, 0.05f, 0.06f};
};

/// A lamp of the scene, in Blender's terms and units (docs/scene-format.md, `lights`).
struct Light {
  enum class Type { Sun, Spot, Point };
  Type type = Type::Sun;
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  ///< Sun and spot: the way the light travels (a lamp's -Z), unit.
  glm::vec3 position{0.0f};                ///< Spot and point: world position.
  glm::vec3 color{1.0f};                   ///< Linear RGB.
  float strength = 1.0f;  ///< Sun: irradiance in W/m^2; spot and point: power in W (Blender's units).
  float spotAngleDegrees = 45.0f;  ///< Spot: full cone angle (Blender's spot_size).
};

inline bool operator==(const Light& a, const Light& b) {
  return a.type == b.type && a.direction == b.direction && a.position == b.position && a.color == b.color &&
         a.strength == b.strength && a.spotAngleDegrees == b.spotAngleDegrees;
}

/// A scene file, version 1 (docs/scene-format.md), parsed and validated.
struct Scene {
  std::filesystem::path file;
  Camera camera;
  std::vector<ParticleSource> particles;
  Background background;
  /// Solid geometry drawn into the depth prepass (the frame's solid depth is the nearer of it and the
  /// background's depth).
  std::vector<MeshSource> occluders;
  /// The liquid's own surface, whose depth plays the role of `background.liquid_depth`.
  std::optional<MeshSource> liquidMesh;
  std::vector<Light> lights;  ///< Empty: the liquid casts no shadow and no caustics.
  Parameters parameters;
  int frame = 1;  ///< The frame rendered when the command line names none.
};

/// Reads and validates a scene file; throws Error naming the file and key at fault.
Scene loadScene(const std::filesystem::path& sceneFile);
/// The same from text; `sceneFile` names it in messages and anchors relative paths.
Scene parseScene(const std::string& jsonText, const std::filesystem::path& sceneFile);

/// Replaces a run of `#` in the file name with the zero-padded frame number; paths without `#` are returned
/// as they are.
std::filesystem::path pathForFrame(const std::filesystem::path& pattern, int frame);

/// Reads every particle source of a frame and brings it to world space. Particles with a non-finite position,
/// or a radius that is not finite and positive, are dropped and counted in `counts->droppedInvalid`.
Particles loadParticles(const Scene& scene, int frame, ParticleCounts* counts = nullptr);

/// Reads a frame's `occluders` and `liquid_mesh` files into `inputs` (world space), beside what it already
/// holds; an in-memory liquid mesh already in `inputs` wins over the scene's file.
void loadMeshes(const Scene& scene, int frame, FrameInputs& inputs);

}  // namespace spindrift
