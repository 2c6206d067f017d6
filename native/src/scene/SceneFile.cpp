#include <fstream>
#include <sstream>

#include <glm/geometric.hpp>

#include "scene/JsonFields.h"
#include "spindrift/Error.h"
#include "spindrift/Scene.h"

namespace spindrift {
namespace {

using nlohmann::json;

constexpr int kMaximumImageSide = 16384;

bool isFramePattern(const std::filesystem::path& path) {
  return path.filename().string().find('#') != std::string::npos;
}

// Paths without `####` are checked now, so a farm job fails before it renders anything.
void requireExisting(const JsonFields& fields, const char* key, const std::filesystem::path& path) {
  if (!isFramePattern(path) && !std::filesystem::exists(path)) fields.fail(key, "no such file: " + path.string());
}

Camera readCamera(const JsonFields& fields) {
  fields.allowOnly({"width", "height", "fov_y_deg", "near", "far", "world_from_camera", "position", "target", "up"});
  Camera camera;
  camera.width = fields.integer("width", 1, kMaximumImageSide);
  camera.height = fields.integer("height", 1, kMaximumImageSide);
  camera.fovYDegrees = fields.number("fov_y_deg", 0.0f, 179.0f);
  if (fields.has("near")) camera.nearClip = fields.number("near", 0.0f, 1e30f);
  if (fields.has("far")) camera.farClip = fields.number("far", 0.0f, 1e30f);
  if (!(camera.farClip > camera.nearClip)) fields.fail("far", "must be greater than near");

  const bool hasMatrix = fields.has("world_from_camera");
  const bool hasLookAt = fields.has("position") || fields.has("target") || fields.has("up");
  if (hasMatrix && hasLookAt) fields.fail("world_from_camera", "give either it or position/target/up, not both");
  if (hasMatrix) {
    // Blender ignores a camera object's scale when it renders: normalise the axes the same way.
    camera.worldFromCamera = fields.affineMatrix("world_from_camera");
    for (int axis = 0; axis < 3; ++axis)
      camera.worldFromCamera[axis] = glm::vec4(glm::normalize(glm::vec3(camera.worldFromCamera[axis])), 0.0f);
  } else if (hasLookAt) {
    const glm::vec3 position = fields.vec3("position"), target = fields.vec3("target"), up = fields.vec3("up");
    const glm::vec3 forward = target - position;
    if (!(glm::length(forward) > 0.0f)) fields.fail("target", "must differ from position");
    if (!(glm::length(glm::cross(forward, up)) > 1e-6f * glm::length(forward) * glm::length(up)))
      fields.fail("up", "must not be parallel to the view direction");
    const Camera lookAt = Camera::lookAt(camera.width, camera.height, camera.fovYDegrees, position, target, up);
    camera.worldFromCamera = lookAt.worldFromCamera;
  } else {
    fields.fail("world_from_camera", "missing (or give position, target and up)");
  }
  return camera;
}

ParticleSource readParticleSource(const JsonFields& fields, const std::filesystem::path& baseDirectory) {
  fields.allowOnly({"path", "grid", "role", "kind", "radius", "world_from_file"});
  ParticleSource source;
  source.path = fields.path("path", baseDirectory);
  const std::string extension = source.path.extension().string();
  if (extension != ".vdb" && extension != ".ply") fields.fail("path", "expected a .vdb or .ply file");
  requireExisting(fields, "path", source.path);
  if (fields.has("grid")) {
    if (extension != ".vdb") fields.fail("grid", "only .vdb files have grids");
    source.grid = fields.string("grid");
  }
  if (fields.has("role")) {
    const std::string role = fields.string("role");
    if (role == "liquid") source.role = ParticleRole::Liquid;
    else if (role == "foam") source.role = ParticleRole::Foam;
    else fields.fail("role", "\"" + role + "\" is not one of liquid, foam");
  }
  if (fields.has("kind")) {
    if (source.role != ParticleRole::Foam) fields.fail("kind", "only foam sources have a kind");
    const std::string kind = fields.string("kind");
    if (kind == "spray") source.kind = ParticleKind::Spray;
    else if (kind == "bubble") source.kind = ParticleKind::Bubble;
    else if (kind == "foam") source.kind = ParticleKind::Foam;
    else fields.fail("kind", "\"" + kind + "\" is not one of spray, bubble, foam");
  }
  source.radius = fields.number("radius", 0.0f, 1e30f);
  if (fields.has("world_from_file")) source.worldFromFile = fields.affineMatrix("world_from_file");
  return source;
}

MeshSource readMeshSource(const JsonFields& fields, const std::filesystem::path& baseDirectory) {
  fields.allowOnly({"path", "world_from_file"});
  MeshSource source;
  source.path = fields.path("path", baseDirectory);
  if (source.path.extension() != ".obj") fields.fail("path", "expected a Wavefront .obj file");
  requireExisting(fields, "path", source.path);
  if (fields.has("world_from_file")) source.worldFromFile = fields.affineMatrix("world_from_file");
  return source;
}

Background readBackground(const JsonFields& fields, const std::filesystem::path& baseDirectory) {
  fields.allowOnly({"image", "depth", "liquid_depth", "environment", "color"});
  Background background;
  if (fields.has("image")) {
    background.image = fields.path("image", baseDirectory);
    requireExisting(fields, "image", background.image);
  }
  if (fields.has("depth")) {
    background.depth = fields.path("depth", baseDirectory);
    background.depthExplicit = true;
    requireExisting(fields, "depth", background.depth);
  }
  if (fields.has("liquid_depth")) {
    background.liquidDepth = fields.path("liquid_depth", baseDirectory);
    requireExisting(fields, "liquid_depth", background.liquidDepth);
  }
  if (fields.has("environment")) {
    background.environment = fields.path("environment", baseDirectory);
    requireExisting(fields, "environment", background.environment);
  }
  if (fields.has("color")) background.color = fields.color("color");
  return background;
}

}  // namespace

Scene parseScene(const std::string& jsonText, const std::filesystem::path& sceneFile) {
  const std::string fileLabel = sceneFile.string();
  json document;
  try {
    document = json::parse(jsonText);
  } catch (const json::parse_error& error) {
    throw Error(fileLabel + ": not valid JSON: " + error.what());
  }
  const JsonFields root(document, fileLabel, "");
  root.allowOnly(
      {"version", "frame", "camera", "particles", "background", "occluders", "liquid_mesh", "liquid", "foam"});
  if (root.integer("version", 0, 1000) != 1)
    root.fail("version", "this Spindrift reads version 1 scene files");

  const std::filesystem::path baseDirectory = std::filesystem::absolute(sceneFile).parent_path();
  Scene scene;
  scene.file = std::filesystem::absolute(sceneFile).lexically_normal();
  if (root.has("frame")) scene.frame = root.integer("frame", -1000000, 1000000);
  scene.camera = readCamera(root.child("camera"));

  const json& particles = root.raw("particles");
  if (!particles.is_array()) root.fail("particles", "expected a list of particle sources");
  for (std::size_t i = 0; i < particles.size(); ++i)
    scene.particles.push_back(
        readParticleSource(JsonFields(particles[i], fileLabel, "particles[" + std::to_string(i) + "]"), baseDirectory));

  if (root.has("occluders")) {
    const json& occluders = root.raw("occluders");
    if (!occluders.is_array()) root.fail("occluders", "expected a list of meshes");
    for (std::size_t i = 0; i < occluders.size(); ++i)
      scene.occluders.push_back(
          readMeshSource(JsonFields(occluders[i], fileLabel, "occluders[" + std::to_string(i) + "]"), baseDirectory));
  }
  if (root.has("liquid_mesh")) scene.liquidMesh = readMeshSource(root.child("liquid_mesh"), baseDirectory);
  if (root.has("background")) scene.background = readBackground(root.child("background"), baseDirectory);
  for (const char* group : {"liquid", "foam"})
    if (root.has(group)) setParameterGroup(scene.parameters, group, root.raw(group), fileLabel);
  return scene;
}

Scene loadScene(const std::filesystem::path& sceneFile) {
  std::ifstream stream(sceneFile);
  if (!stream) throw Error(sceneFile.string() + ": cannot open the scene file");
  std::stringstream text;
  text << stream.rdbuf();
  return parseScene(text.str(), sceneFile);
}

}  // namespace spindrift
