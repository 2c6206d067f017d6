#include <gtest/gtest.h>

#include <glm/gtc/matrix_access.hpp>

#include "TempDirectory.h"
#include "spindrift/Error.h"
#include "spindrift/Scene.h"

using namespace spindrift;

namespace {

const char* kParticlesPly =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "end_header\n0 0 0\n1 0 0\nnan 0 0\n";

std::string sceneWith(const std::string& cameraExtra, const std::string& rest = "") {
  return R"({"version": 1, "camera": {"width": 64, "height": 32, "fov_y_deg": 40)" + cameraExtra + "}," +
         R"("particles": [{"path": "p.ply", "radius": 0.1}])" + rest + "}";
}

const std::string kLookAt = R"(, "position": [0, -5, 1], "target": [0, 0, 1], "up": [0, 0, 1])";

// Parses a scene from text in a directory that holds p.ply; returns the error message, or "" on success.
std::string errorOf(const std::string& text) {
  TempDirectory directory;
  directory.write("p.ply", kParticlesPly);
  try {
    parseScene(text, directory.path() / "scene.json");
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST(SceneFile, ReadsAMinimalSceneWithDefaults) {
  TempDirectory directory;
  directory.write("p.ply", kParticlesPly);
  const Scene scene = parseScene(sceneWith(kLookAt), directory.path() / "scene.json");
  EXPECT_EQ(scene.camera.width, 64);
  EXPECT_EQ(scene.camera.height, 32);
  EXPECT_FLOAT_EQ(scene.camera.nearClip, 0.01f);
  EXPECT_FLOAT_EQ(scene.camera.farClip, 1000.0f);
  EXPECT_EQ(scene.frame, 1);
  ASSERT_EQ(scene.particles.size(), 1u);
  EXPECT_EQ(scene.particles[0].path, directory.path() / "p.ply");
  EXPECT_EQ(scene.particles[0].role, ParticleRole::Liquid);
  // The camera at (0,-5,1) looking at (0,0,1): its -Z axis is world +Y, its +Y axis world +Z.
  EXPECT_NEAR(glm::column(scene.camera.worldFromCamera, 2).y, -1.0f, 1e-6f);
  EXPECT_NEAR(glm::column(scene.camera.worldFromCamera, 1).z, 1.0f, 1e-6f);
}

TEST(SceneFile, WorldFromCameraIsRowMajor) {
  TempDirectory directory;
  directory.write("p.ply", kParticlesPly);
  // Row-major: the translation is the last column of the rows as written.
  const Scene scene = parseScene(sceneWith(R"(, "world_from_camera": [1,0,0,3, 0,1,0,4, 0,0,1,5, 0,0,0,1])"),
                                 directory.path() / "s.json");
  EXPECT_EQ(scene.camera.position(), glm::vec3(3, 4, 5));
}

TEST(SceneFile, LoadsParticlesToWorldDroppingNaN) {
  TempDirectory directory;
  directory.write("p.ply", kParticlesPly);
  const Scene scene = parseScene(
      R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40, "position": [0,-5,0],
          "target": [0,0,0], "up": [0,0,1]},
          "particles": [{"path": "p.ply", "radius": 0.25, "role": "foam", "kind": "spray",
                         "world_from_file": [2,0,0,10, 0,2,0,0, 0,0,2,0, 0,0,0,1]}]})",
      directory.path() / "scene.json");
  ParticleCounts counts;
  const Particles particles = loadParticles(scene, 1, &counts);
  ASSERT_EQ(particles.size(), 2u);
  EXPECT_EQ(particles.positions[1], glm::vec3(12, 0, 0));
  EXPECT_EQ(particles.kinds[0], ParticleKind::Spray);
  EXPECT_FLOAT_EQ(particles.radii[0], 0.25f);
  EXPECT_EQ(counts.spray, 2u);
  EXPECT_EQ(counts.droppedInvalid, 1u);
}

TEST(SceneFile, FramePatternIsZeroPadded) {
  EXPECT_EQ(pathForFrame("/c/fluid_data_####.vdb", 7), std::filesystem::path("/c/fluid_data_0007.vdb"));
  EXPECT_EQ(pathForFrame("/c/p_#.ply", 123), std::filesystem::path("/c/p_123.ply"));
  EXPECT_EQ(pathForFrame("/c#/plain.ply", 5), std::filesystem::path("/c#/plain.ply"));
}

TEST(SceneFile, MissingFrameFileNamesTheFrame) {
  TempDirectory directory;
  directory.write("p_0001.ply", kParticlesPly);
  const Scene scene = parseScene(
      R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40, "position": [0,-5,0],
          "target": [0,0,0], "up": [0,0,1]}, "particles": [{"path": "p_####.ply", "radius": 1}]})",
      directory.path() / "scene.json");
  EXPECT_EQ(loadParticles(scene, 1).size(), 2u);
  try {
    loadParticles(scene, 2);
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("p_0002.ply"), std::string::npos) << error.what();
  }
}

// Foam over a full render: the depth of the render with the liquid is a path of its own beside the solids'.
TEST(SceneFile, ReadsBackgroundLiquidDepth) {
  TempDirectory directory;
  directory.write("p.ply", kParticlesPly);
  directory.write("with_liquid.exr", "");
  directory.write("background.exr", "");
  const Scene scene =
      parseScene(sceneWith(kLookAt, R"(, "background": {"image": "with_liquid.exr", "depth": "background.exr",
                              "liquid_depth": "with_liquid.exr"}, "foam": {"ao_passes": 2})"),
                 directory.path() / "scene.json");
  EXPECT_EQ(scene.background.liquidDepth, directory.path() / "with_liquid.exr");
  EXPECT_EQ(scene.background.depth, directory.path() / "background.exr");
  EXPECT_EQ(scene.parameters.foam.ao_passes, 2);
  EXPECT_TRUE(parseScene(sceneWith(kLookAt), directory.path() / "s.json").background.liquidDepth.empty());
}

// Lights in Blender's terms: a sun's direction (normalised), spot and point positions, watts, the cone.
TEST(SceneFile, ReadsLights) {
  TempDirectory directory;
  directory.write("p.ply", kParticlesPly);
  const Scene scene = parseScene(sceneWith(kLookAt, R"(, "lights": [
        {"type": "sun", "direction": [0, 3, -4], "strength": 3.5, "color": [1, 0.9, 0.8]},
        {"type": "spot", "position": [1, 2, 3], "direction": [0, 0, -1], "strength": 800, "spot_angle_deg": 30},
        {"type": "point", "position": [0, 0, 5], "strength": 1000}], "light": {"shadow_map_size": 256})"),
                                 directory.path() / "scene.json");
  ASSERT_EQ(scene.lights.size(), 3u);
  EXPECT_EQ(scene.lights[0].type, Light::Type::Sun);
  EXPECT_NEAR(scene.lights[0].direction.y, 0.6f, 1e-6f);
  EXPECT_NEAR(scene.lights[0].direction.z, -0.8f, 1e-6f);
  EXPECT_FLOAT_EQ(scene.lights[0].strength, 3.5f);
  EXPECT_FLOAT_EQ(scene.lights[0].color.b, 0.8f);
  EXPECT_EQ(scene.lights[1].type, Light::Type::Spot);
  EXPECT_FLOAT_EQ(scene.lights[1].spotAngleDegrees, 30.0f);
  EXPECT_FLOAT_EQ(scene.lights[1].position.z, 3.0f);
  EXPECT_EQ(scene.lights[2].type, Light::Type::Point);
  EXPECT_FLOAT_EQ(scene.lights[2].color.g, 1.0f);
  EXPECT_EQ(scene.parameters.light.shadow_map_size, 256);
  EXPECT_TRUE(parseScene(sceneWith(kLookAt), directory.path() / "s.json").lights.empty());
}

TEST(SceneFile, DomainSettingsWithACellSizeDeriveTheRadius) {
  TempDirectory directory;
  directory.write("p.ply", kParticlesPly);
  // particle_number 3: particles a third of a cell apart, r = 1.1 spacings; no cache beside p.ply, so the
  // cell size is the scene's.
  const Scene scene = parseScene(
      R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
          R"(}, "particles": [{"path": "p.ply", "domain": {"cell_size": 0.3, "particle_number": 3}}]})",
      directory.path() / "scene.json");
  EXPECT_NEAR(scene.particles[0].radius, 0.11f, 1e-6f);
  EXPECT_NE(scene.particles[0].radiusOrigin.find("particle_number 3"), std::string::npos);
  EXPECT_GT(scene.parameters.liquid.surface_offset, 0.0f);
  // Old scene files: a hand radius and no domain leave the surface offset at 0, so they render as before.
  EXPECT_FLOAT_EQ(
      parseScene(sceneWith(kLookAt), directory.path() / "s.json").parameters.liquid.surface_offset, 0.0f);
}

TEST(SceneFile, AGivenSurfaceOffsetWinsOverTheDerivedOne) {
  TempDirectory directory;
  directory.write("p.ply", kParticlesPly);
  const Scene scene = parseScene(
      R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
          R"(}, "particles": [{"path": "p.ply", "domain": {"cell_size": 0.3}}], "liquid": {"surface_offset": 0.25}})",
      directory.path() / "scene.json");
  EXPECT_FLOAT_EQ(scene.parameters.liquid.surface_offset, 0.25f);
}

// Each bad file gets one error that names the key at fault.
struct BadScene {
  const char* name;
  std::string text;
  const char* expectedInMessage;
};

// Test listings show the case's name, not the bytes of the struct.
void PrintTo(const BadScene& scene, std::ostream* out) {
  *out << scene.name;
}

class SceneFileErrors : public testing::TestWithParam<BadScene> {};

TEST_P(SceneFileErrors, NameTheKey) {
  const std::string message = errorOf(GetParam().text);
  ASSERT_FALSE(message.empty()) << "accepted a bad scene";
  EXPECT_NE(message.find("scene.json"), std::string::npos) << message;
  EXPECT_NE(message.find(GetParam().expectedInMessage), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SceneFileErrors,
    testing::Values(
        BadScene{"NotJson", "{\"version\": 1,", "not valid JSON"},
        BadScene{"NotAnObject", "[1, 2]", "expected an object"},
        BadScene{"WrongVersion", R"({"version": 2})", "version"},
        BadScene{"UnknownTopLevelKey", sceneWith(kLookAt, R"(, "liquidd": {})"), "liquidd"},
        BadScene{"MissingCamera", R"({"version": 1, "particles": []})", "camera"},
        BadScene{"ZeroWidth",
                 R"({"version": 1, "camera": {"width": 0, "height": 32, "fov_y_deg": 40)" + kLookAt +
                     "}, \"particles\": []}",
                 "camera.width"},
        BadScene{"FractionalHeight",
                 R"({"version": 1, "camera": {"width": 8, "height": 3.5, "fov_y_deg": 40)" + kLookAt +
                     "}, \"particles\": []}",
                 "camera.height"},
        BadScene{"FovOutOfRange",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 180)" + kLookAt +
                     "}, \"particles\": []}",
                 "camera.fov_y_deg"},
        BadScene{"FarBeforeNear", sceneWith(kLookAt + R"(, "near": 1, "far": 0.5)"), "camera.far"},
        BadScene{"NoCameraPose", sceneWith(""), "camera.world_from_camera"},
        BadScene{"BothPoses",
                 sceneWith(kLookAt + R"(, "world_from_camera": [1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1])"),
                 "camera.world_from_camera"},
        BadScene{"ShortMatrix", sceneWith(R"(, "world_from_camera": [1,0,0])"), "camera.world_from_camera"},
        BadScene{"SingularMatrix", sceneWith(R"(, "world_from_camera": [0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,1])"),
                 "singular"},
        BadScene{"ProjectiveMatrix", sceneWith(R"(, "world_from_camera": [1,0,0,0,0,1,0,0,0,0,1,0,0,0,1,1])"),
                 "affine"},
        BadScene{"TargetIsPosition", sceneWith(R"(, "position": [1,1,1], "target": [1,1,1], "up": [0,0,1])"),
                 "camera.target"},
        BadScene{"UpAlongView", sceneWith(R"(, "position": [0,0,0], "target": [0,0,1], "up": [0,0,1])"),
                 "camera.up"},
        BadScene{"ParticlesNotAList",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": {}})",
                 "particles"},
        BadScene{"MissingParticleFile",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "nope.ply", "radius": 1}]})",
                 "particles[0].path"},
        BadScene{"WrongExtension",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "p.txt", "radius": 1}]})",
                 "particles[0].path"},
        BadScene{"NegativeRadius",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "p.ply", "radius": -1}]})",
                 "particles[0].radius"},
        BadScene{"UnknownRole",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "p.ply", "radius": 1, "role": "solid"}]})",
                 "particles[0].role"},
        BadScene{"KindOnLiquid",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "p.ply", "radius": 1, "kind": "spray"}]})",
                 "particles[0].kind"},
        BadScene{"GridOnPly",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "p.ply", "radius": 1, "grid": "x"}]})",
                 "particles[0].grid"},
        BadScene{"TypoInSource",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "p.ply", "raduis": 1}]})",
                 "particles[0].raduis"},
        BadScene{"MissingBackgroundImage", sceneWith(kLookAt, R"(, "background": {"image": "bg.exr"})"),
                 "background.image"},
        BadScene{"MissingLiquidDepth",
                 sceneWith(kLookAt, R"(, "background": {"liquid_depth": "with_liquid.exr"})"),
                 "background.liquid_depth"},
        BadScene{"LiquidDepthNotAString", sceneWith(kLookAt, R"(, "background": {"liquid_depth": 3})"),
                 "background.liquid_depth"},
        BadScene{"TypoInBackground", sceneWith(kLookAt, R"(, "background": {"liquid_dpeth": "p.ply"})"),
                 "background.liquid_dpeth"},
        BadScene{"FoamParameterOutOfRange", sceneWith(kLookAt, R"(, "foam": {"ao_passes": 0})"),
                 "foam.ao_passes"},
        BadScene{"UnknownFoamChoice", sceneWith(kLookAt, R"(, "foam": {"irradiance": "probe"})"),
                 "foam.irradiance"},
        BadScene{"NegativeBackgroundColor", sceneWith(kLookAt, R"(, "background": {"color": [0, -1, 0]})"),
                 "background.color"},
        BadScene{"UnknownParameter", sceneWith(kLookAt, R"(, "liquid": {"absorption_colour": [1, 1, 1]})"),
                 "liquid.absorption_colour"},
        BadScene{"ParameterOutOfRange", sceneWith(kLookAt, R"(, "liquid": {"ior": 7})"), "liquid.ior"},
        BadScene{"LightsNotAList", sceneWith(kLookAt, R"(, "lights": {"type": "sun"})"), "lights"},
        BadScene{"UnknownLightType", sceneWith(kLookAt, R"(, "lights": [{"type": "area", "strength": 1}])"),
                 "lights[0].type"},
        BadScene{"SunWithoutDirection", sceneWith(kLookAt, R"(, "lights": [{"type": "sun", "strength": 1}])"),
                 "lights[0].direction"},
        BadScene{
            "ZeroSunDirection",
            sceneWith(kLookAt, R"(, "lights": [{"type": "sun", "direction": [0, 0, 0], "strength": 1}])"),
            "lights[0].direction"},
        BadScene{
            "PointWithDirection",
            sceneWith(
                kLookAt,
                R"(, "lights": [{"type": "point", "position": [0, 0, 1], "direction": [0, 0, -1], "strength": 1}])"),
            "lights[0].direction"},
        BadScene{
            "SunWithPosition",
            sceneWith(
                kLookAt,
                R"(, "lights": [{"type": "sun", "direction": [0, 0, -1], "position": [0, 0, 1], "strength": 1}])"),
            "lights[0].position"},
        BadScene{
            "NegativeLightStrength",
            sceneWith(kLookAt, R"(, "lights": [{"type": "point", "position": [0, 0, 1], "strength": -2}])"),
            "lights[0].strength"},
        BadScene{
            "ConeOnPoint",
            sceneWith(
                kLookAt,
                R"(, "lights": [{"type": "point", "position": [0, 0, 1], "strength": 1, "spot_angle_deg": 30}])"),
            "lights[0].spot_angle_deg"},
        BadScene{
            "TypoInLight",
            sceneWith(kLookAt, R"(, "lights": [{"type": "sun", "direction": [0, 0, -1], "strenght": 1}])"),
            "lights[0].strenght"},
        BadScene{"LightParameterOutOfRange", sceneWith(kLookAt, R"(, "light": {"direct_fraction": 2})"),
                 "light.direct_fraction"},
        BadScene{"ZeroFov",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 0)" + kLookAt +
                     "}, \"particles\": []}",
                 "camera.fov_y_deg"},
        BadScene{"NearEqualsFar", sceneWith(kLookAt + R"(, "near": 2, "far": 2)"), "camera.far"},
        BadScene{"ZeroNear", sceneWith(kLookAt + R"(, "near": 0)"), "camera.near"},
        BadScene{"WiderThanTheLimit",
                 R"({"version": 1, "camera": {"width": 16385, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     "}, \"particles\": []}",
                 "16384"},
        BadScene{"ZeroRadius",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "p.ply", "radius": 0}]})",
                 "particles[0].radius"},
        BadScene{"InfiniteMatrixElement",
                 sceneWith(R"(, "world_from_camera": [1,0,0,0,0,1,0,0,0,0,1,1e999,0,0,0,1])"),
                 "number overflow parsing '1e999'"},
        BadScene{"NeitherRadiusNorDomain",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "p.ply"}]})",
                 "particles[0].radius: missing: give the particle radius, or the Mantaflow \"domain\""},
        BadScene{"DomainWithoutCacheOrCellSize",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "p.ply", "domain": {}}]})",
                 "particles[0].domain: no Mantaflow config file"},
        BadScene{"TypoInDomain",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "p.ply", "domain": {"mesh_particle_raduis": 2}}]})",
                 "particles[0].domain.mesh_particle_raduis"},
        BadScene{
            "UnknownMeshGenerator",
            R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                R"(}, "particles": [{"path": "p.ply", "domain": {"cell_size": 0.1, "mesh_generator": "FINAL"}}]})",
            "particles[0].domain.mesh_generator"},
        BadScene{"DomainOnFoam",
                 R"({"version": 1, "camera": {"width": 8, "height": 8, "fov_y_deg": 40)" + kLookAt +
                     R"(}, "particles": [{"path": "p.ply", "role": "foam", "radius": 1, "domain": {}}]})",
                 "particles[0].domain"},
        BadScene{"NaNInMatrix", sceneWith(R"(, "world_from_camera": [1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,"x"])"),
                 "camera.world_from_camera"}),
    [](const testing::TestParamInfo<BadScene>& info) { return info.param.name; });
