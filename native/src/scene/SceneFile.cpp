#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <glm/geometric.hpp>

#include "scene/JsonFields.h"
#include "scene/MantaflowDomain.h"
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
  if (!isFramePattern(path) && !std::filesystem::exists(path))
    fields.fail(key, "no such file: " + path.string());
}

Camera readCamera(const JsonFields& fields) {
  fields.allowOnly(
      {"width", "height", "fov_y_deg", "near", "far", "world_from_camera", "position", "target", "up"});
  Camera camera;
  camera.width = fields.integer("width", 1, kMaximumImageSide);
  camera.height = fields.integer("height", 1, kMaximumImageSide);
  camera.fovYDegrees = fields.number("fov_y_deg", 0.0f, 179.0f);
  if (fields.has("near")) camera.nearClip = fields.number("near", 0.0f, 1e30f);
  if (fields.has("far")) camera.farClip = fields.number("far", 0.0f, 1e30f);
  if (!(camera.farClip > camera.nearClip)) fields.fail("far", "must be greater than near");

  const bool hasMatrix = fields.has("world_from_camera");
  const bool hasLookAt = fields.has("position") || fields.has("target") || fields.has("up");
  if (hasMatrix && hasLookAt)
    fields.fail("world_from_camera", "give either it or position/target/up, not both");
  if (hasMatrix) {
    // Blender ignores a camera object's scale when it renders: normalise the axes the same way.
    camera.worldFromCamera = fields.affineMatrix("world_from_camera");
    for (int axis = 0; axis < 3; ++axis)
      camera.worldFromCamera[axis] = glm::vec4(glm::normalize(glm::vec3(camera.worldFromCamera[axis])), 0.0f);
  } else if (hasLookAt) {
    const glm::vec3 position = fields.vec3("position"), target = fields.vec3("target"),
                    up = fields.vec3("up");
    const glm::vec3 forward = target - position;
    if (!(glm::length(forward) > 0.0f)) fields.fail("target", "must differ from position");
    if (!(glm::length(glm::cross(forward, up)) > 1e-6f * glm::length(forward) * glm::length(up)))
      fields.fail("up", "must not be parallel to the view direction");
    const Camera lookAt =
        Camera::lookAt(camera.width, camera.height, camera.fovYDegrees, position, target, up);
    camera.worldFromCamera = lookAt.worldFromCamera;
  } else {
    fields.fail("world_from_camera", "missing (or give position, target and up)");
  }
  return camera;
}

// A liquid source's `domain`: the Mantaflow settings that shape the liquid mesh, every key optional with
// Blender's default. The cell size and the domain's transform come from the cache's config files.
MantaflowDomainSettings readDomainSettings(const JsonFields& fields) {
  fields.allowOnly({"particle_radius", "mesh_particle_radius", "mesh_scale", "mesh_smoothen_pos",
                    "mesh_smoothen_neg", "mesh_concave_upper", "mesh_concave_lower", "particle_number",
                    "mesh_generator", "cell_size"});
  MantaflowDomainSettings settings;
  if (fields.has("particle_radius")) settings.particleRadius = fields.number("particle_radius", 0.0f, 10.0f);
  if (fields.has("mesh_particle_radius"))
    settings.meshParticleRadius = fields.number("mesh_particle_radius", 0.0f, 10.0f);
  if (fields.has("mesh_scale")) settings.meshScale = fields.integer("mesh_scale", 1, 100);
  if (fields.has("mesh_smoothen_pos")) settings.meshSmoothenPos = fields.integer("mesh_smoothen_pos", 0, 100);
  if (fields.has("mesh_smoothen_neg")) settings.meshSmoothenNeg = fields.integer("mesh_smoothen_neg", 0, 100);
  if (fields.has("mesh_concave_upper"))
    settings.meshConcaveUpper = fields.number("mesh_concave_upper", -1.0f, 10.0f);
  if (fields.has("mesh_concave_lower"))
    settings.meshConcaveLower = fields.number("mesh_concave_lower", -1.0f, 10.0f);
  if (fields.has("particle_number")) settings.particleNumber = fields.integer("particle_number", 1, 5);
  if (fields.has("mesh_generator")) {
    const std::string generator = fields.string("mesh_generator");
    if (generator == "IMPROVED")
      settings.improvedMesh = true;
    else if (generator == "UNION")
      settings.improvedMesh = false;
    else
      fields.fail("mesh_generator", "\"" + generator + "\" is not one of IMPROVED, UNION");
  }
  if (fields.has("cell_size")) settings.cellSize = fields.number("cell_size", 0.0f, 1e30f);
  return settings;
}

// Radius, surface offset and (when the scene gives none) world_from_file from the source's Mantaflow domain.
void applyDomain(const JsonFields& fields, ParticleSource& source) {
  const MantaflowDomainSettings settings = readDomainSettings(fields.child("domain"));
  float cellSize = settings.cellSize;
  const std::filesystem::path configPath = findMantaflowCacheConfig(source.path);
  if (!configPath.empty()) {
    const MantaflowCacheConfig config = readMantaflowCacheConfig(configPath);
    if (cellSize == 0.0f) cellSize = config.cellSize();
    if (!fields.has("world_from_file")) source.worldFromFile = config.worldFromFile();
    // Mantaflow sets the outermost mesh_scale - 1 layers of mesh cells outside (0.5), so the mesh's face
    // against a wall lies about one mesh cell less than that inside: (mesh_scale - 0.1) mesh cells.
    const float inset = (float(settings.meshScale) - 0.1f) / float(settings.meshScale) * config.cellSize();
    source.domainBox = DomainBox{config.worldFromFile(), glm::vec3(inset),
                                 glm::vec3(config.resolution) * config.cellSize() - inset};
  } else if (cellSize == 0.0f) {
    fields.fail("domain", "no Mantaflow config file (cache/config/config_NNNN.uni) beside " +
                              source.path.string() + ": give domain.cell_size");
  }
  const LiquidSurfaceFromDomain surface = liquidSurfaceFromDomain(settings, cellSize);
  source.meshFlatOffset = surface.flatOffset;
  source.meshKernelRadius = surface.meshKernelRadius;
  if (!fields.has("radius")) {
    source.radius = surface.radius;
    source.radiusOrigin = surface.origin;
  }
}

ParticleSource readParticleSource(const JsonFields& fields, const std::filesystem::path& baseDirectory) {
  fields.allowOnly({"path", "grid", "role", "kind", "radius", "domain", "world_from_file"});
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
    if (role == "liquid")
      source.role = ParticleRole::Liquid;
    else if (role == "foam")
      source.role = ParticleRole::Foam;
    else
      fields.fail("role", "\"" + role + "\" is not one of liquid, foam");
  }
  if (fields.has("kind")) {
    if (source.role != ParticleRole::Foam) fields.fail("kind", "only foam sources have a kind");
    const std::string kind = fields.string("kind");
    if (kind == "spray")
      source.kind = ParticleKind::Spray;
    else if (kind == "bubble")
      source.kind = ParticleKind::Bubble;
    else if (kind == "foam")
      source.kind = ParticleKind::Foam;
    else
      fields.fail("kind", "\"" + kind + "\" is not one of spray, bubble, foam");
  }
  if (fields.has("radius")) source.radius = fields.number("radius", 0.0f, 1e30f);
  if (fields.has("world_from_file")) source.worldFromFile = fields.affineMatrix("world_from_file");
  if (fields.has("domain")) {
    if (source.role != ParticleRole::Liquid) fields.fail("domain", "only liquid sources have a domain");
    applyDomain(fields, source);
  } else if (!fields.has("radius")) {
    fields.fail("radius",
                source.role == ParticleRole::Liquid
                    ? "missing: give the particle radius, or the Mantaflow \"domain\" to derive it from"
                    : "missing");
  }
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

Light readLight(const JsonFields& fields) {
  fields.allowOnly({"type", "direction", "position", "color", "strength", "spot_angle_deg"});
  Light light;
  const std::string type = fields.string("type");
  if (type == "sun")
    light.type = Light::Type::Sun;
  else if (type == "spot")
    light.type = Light::Type::Spot;
  else if (type == "point")
    light.type = Light::Type::Point;
  else
    fields.fail("type", "\"" + type + "\" is not one of sun, spot, point");
  const bool directional = light.type != Light::Type::Point;
  if (directional) {
    light.direction = fields.vec3("direction");
    if (!(glm::length(light.direction) > 0.0f)) fields.fail("direction", "must not be zero");
    light.direction = glm::normalize(light.direction);
  } else if (fields.has("direction")) {
    fields.fail("direction", "a point light has no direction");
  }
  if (light.type != Light::Type::Sun)
    light.position = fields.vec3("position");
  else if (fields.has("position"))
    fields.fail("position", "a sun has no position (only a direction)");
  if (light.type == Light::Type::Spot) {
    if (fields.has("spot_angle_deg")) light.spotAngleDegrees = fields.number("spot_angle_deg", 0.0f, 180.0f);
  } else if (fields.has("spot_angle_deg")) {
    fields.fail("spot_angle_deg", "only spot lights have a cone");
  }
  if (fields.has("color")) light.color = fields.color("color");
  light.strength = fields.number("strength", -1.0f, 1e30f);
  if (light.strength < 0.0f) fields.fail("strength", "must not be negative");
  return light;
}

// Sources derived from Mantaflow domains set liquid.surface_offset, in radii, so the drawn surface stands
// where Mantaflow's flat surface stands: its offset minus what Spindrift's own flat surface already reaches;
// and liquid.mesh_kernel_radius, Mantaflow's r_m in radii, which sizes the splashes. Either is left alone
// where the scene's "liquid" group gives it.
void applyDerivedMeshSettings(const JsonFields& root, Scene& scene) {
  const bool hasLiquidGroup = root.has("liquid") && root.raw("liquid").is_object();
  const auto given = [&](const char* key) { return hasLiquidGroup && root.raw("liquid").contains(key); };
  float derivedOffset = -1.0f, derivedKernel = -1.0f;
  for (std::size_t i = 0; i < scene.particles.size(); ++i) {
    const ParticleSource& source = scene.particles[i];
    if (source.meshFlatOffset <= 0.0f) continue;
    const float offset = std::max(0.0f, source.meshFlatOffset / source.radius - kSpindriftFlatOffsetRadii);
    const float kernel = source.meshKernelRadius / source.radius;
    const auto differs = [](float a, float b) {
      return b >= 0.0f && std::abs(a - b) > 1e-3f * std::max(1.0f, b);
    };
    if ((!given("surface_offset") && differs(offset, derivedOffset)) ||
        (!given("mesh_kernel_radius") && differs(kernel, derivedKernel)))
      root.fail("particles[" + std::to_string(i) + "].domain",
                "its surface offset (" + std::to_string(offset) + " radii) or mesh kernel radius (" +
                    std::to_string(kernel) +
                    " radii) differs from another liquid source's; set liquid.surface_offset and "
                    "liquid.mesh_kernel_radius");
    derivedOffset = offset;
    derivedKernel = kernel;
  }
  if (derivedOffset >= 0.0f && !given("surface_offset"))
    scene.parameters.liquid.surface_offset = std::min(derivedOffset, 100.0f);
  if (derivedKernel >= 0.0f && !given("mesh_kernel_radius"))
    scene.parameters.liquid.mesh_kernel_radius = std::min(derivedKernel, 100.0f);
}

}  // namespace

Scene parseScene(const std::string& jsonText, const std::filesystem::path& sceneFile) {
  const std::string fileLabel = sceneFile.string();
  json document;
  try {
    document = json::parse(jsonText);
  } catch (const json::exception& error) {
    // parse_error for bad syntax, out_of_range for a number beyond double (1e999): both are bad JSON here.
    throw Error(fileLabel + ": not valid JSON: " + error.what());
  }
  const JsonFields root(document, fileLabel, "");
  root.allowOnly({"version", "frame", "camera", "particles", "background", "occluders", "liquid_mesh",
                  "lights", "liquid", "foam", "light"});
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
    scene.particles.push_back(readParticleSource(
        JsonFields(particles[i], fileLabel, "particles[" + std::to_string(i) + "]"), baseDirectory));

  if (root.has("occluders")) {
    const json& occluders = root.raw("occluders");
    if (!occluders.is_array()) root.fail("occluders", "expected a list of meshes");
    for (std::size_t i = 0; i < occluders.size(); ++i)
      scene.occluders.push_back(readMeshSource(
          JsonFields(occluders[i], fileLabel, "occluders[" + std::to_string(i) + "]"), baseDirectory));
  }
  if (root.has("liquid_mesh")) scene.liquidMesh = readMeshSource(root.child("liquid_mesh"), baseDirectory);
  if (root.has("background")) scene.background = readBackground(root.child("background"), baseDirectory);
  if (root.has("lights")) {
    const json& lights = root.raw("lights");
    if (!lights.is_array()) root.fail("lights", "expected a list of lights");
    for (std::size_t i = 0; i < lights.size(); ++i)
      scene.lights.push_back(
          readLight(JsonFields(lights[i], fileLabel, "lights[" + std::to_string(i) + "]")));
  }
  for (const char* group : {"liquid", "foam", "light"})
    if (root.has(group)) setParameterGroup(scene.parameters, group, root.raw(group), fileLabel);
  applyDerivedMeshSettings(root, scene);
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
