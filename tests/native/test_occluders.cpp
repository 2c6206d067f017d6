// The occluder depth prepass and its inputs: the OBJ reader, the scene file's `occluders` and `liquid_mesh`,
// and the pass's depth against a CPU ray-triangle reference. GL tests run on whatever EGL gives (llvmpipe).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <glm/glm.hpp>

#include "Readback.h"
#include "TempDirectory.h"
#include "gl/GlThread.h"
#include "gl/ShaderLibrary.h"
#include "io/MeshFile.h"
#include "passes/FrameUniforms.h"
#include "passes/OccluderDepthPass.h"
#include "spindrift/Error.h"
#include "spindrift/Renderer.h"
#include "spindrift/Scene.h"

using namespace spindrift;

namespace {

TEST(ObjReader, ReadsVerticesAndSplitsPolygonsIntoFans) {
  TempDirectory directory;
  const auto path =
      directory.write("mesh.obj",
                      "# a quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1.0\nvn 0 0 1\n"
                      "vt 0 0\ng quad\nf 1/1/1 2/1/1 3//1 4\nf -4 -3 -1\n");
  const TriangleMesh mesh = readObjMesh(path);
  ASSERT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.vertices[2], glm::vec3(1, 1, 0));
  ASSERT_EQ(mesh.triangles.size(), 3u);
  EXPECT_EQ(mesh.triangles[0], glm::uvec3(0, 1, 2));
  EXPECT_EQ(mesh.triangles[1], glm::uvec3(0, 2, 3));
  EXPECT_EQ(mesh.triangles[2], glm::uvec3(0, 1, 3));
}

struct BadObj {
  const char* name;
  const char* text;
  const char* message;
};

class ObjReaderErrors : public testing::TestWithParam<BadObj> {};

TEST_P(ObjReaderErrors, NameTheLine) {
  TempDirectory directory;
  const auto path = directory.write("bad.obj", GetParam().text);
  try {
    readObjMesh(path);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(GetParam().message), std::string::npos) << error.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ObjReaderErrors,
    testing::Values(BadObj{"IndexBeyondVertices", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
                           "line 4: vertex index 4 is outside the 3 vertices"},
                    BadObj{"IndexZero", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "vertex index 0"},
                    BadObj{"NegativeTooFar", "v 0 0 0\nf -1 -2 -3\n", "vertex index -2"},
                    BadObj{"TwoCorners", "v 0 0 0\nv 1 0 0\nf 1 2\n", "at least three"},
                    BadObj{"ShortVertex", "v 0 0\n", "line 1: expected 'v x y z'"},
                    BadObj{"NotANumber", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 b 3\n", "'b' is not a vertex index"},
                    BadObj{"NonFinite", "v 0 nan 0\n", "not finite"}),
    [](const testing::TestParamInfo<BadObj>& info) { return info.param.name; });

// The planar eye depth at a pixel centre of the plane through a triangle, or NaN where the centre is outside
// the triangle or within `margin` pixels of an edge (GL snaps vertices to sub-pixel precision there).
double referenceDepth(const Camera& camera, const glm::vec3 corners[3], int column, int row, double margin) {
  glm::dvec2 pixel[3];
  for (int i = 0; i < 3; ++i)
    pixel[i] = glm::dvec2(glm::vec2(camera.pixelAndDepthFromWorld(corners[i])));
  const glm::dvec2 centre(column + 0.5, row + 0.5);
  double signs[3];
  for (int i = 0; i < 3; ++i) {
    const glm::dvec2 p = pixel[i], q = pixel[(i + 1) % 3];
    signs[i] = ((q.x - p.x) * (centre.y - p.y) - (q.y - p.y) * (centre.x - p.x)) / glm::length(q - p);
    if (std::abs(signs[i]) < margin) return NAN;
  }
  const bool inside =
      (signs[0] > 0 && signs[1] > 0 && signs[2] > 0) || (signs[0] < 0 && signs[1] < 0 && signs[2] < 0);
  if (!inside) return NAN;
  // The camera ray with z = -1 (its parameter is planar eye depth) against the triangle's plane.
  const double tanHalfY = std::tan(glm::radians(double(camera.fovYDegrees)) * 0.5);
  const glm::dvec3 ray((centre.x / camera.width * 2.0 - 1.0) * tanHalfY * camera.aspect(),
                       (1.0 - centre.y / camera.height * 2.0) * tanHalfY, -1.0);
  const glm::dmat4 cameraFromWorld = glm::inverse(glm::dmat4(camera.worldFromCamera));
  glm::dvec3 eye[3];
  for (int i = 0; i < 3; ++i)
    eye[i] = glm::dvec3(cameraFromWorld * glm::dvec4(glm::dvec3(corners[i]), 1.0));
  const glm::dvec3 normal = glm::cross(eye[1] - eye[0], eye[2] - eye[0]);
  return glm::dot(normal, eye[0]) / glm::dot(normal, ray);
}

// The prepass on a GL thread of its own.
class PrepassHarness {
 public:
  PrepassHarness() {
    glThread_.run([this] { pipeline_ = std::make_unique<Pipeline>(); });
  }
  ~PrepassHarness() {
    glThread_.run([this] { pipeline_.reset(); });
  }
  std::vector<float> run(const Camera& camera, const std::vector<const TriangleMesh*>& meshes,
                         const std::vector<float>* startDepth) {
    return glThread_.run([&] {
      pipeline_->frameUniforms.update(camera);
      if (startDepth)
        uploadTexture(pipeline_->start, GL_R32F, camera.width, camera.height, 1, startDepth->data(), false);
      const OccluderDepthData depth = pipeline_->prepass.run(meshes, startDepth ? &pipeline_->start : nullptr,
                                                             camera.width, camera.height);
      return readLayer(depth.eyeDepth, "depth", {"Z"}).pixels;
    });
  }

 private:
  struct Pipeline {
    ShaderLibrary shaders{findShaderDirectory()};
    FrameUniformBuffer frameUniforms;
    OccluderDepthPass prepass{shaders};
    Texture2D start;
  };
  GlThread glThread_;
  std::unique_ptr<Pipeline> pipeline_;
};

// Two slanted triangles that cross each other, drawn over a start depth that is nearer on the left third, and
// over nothing (the pass clears to "no surface" itself): both against ray casts of the triangles' planes.
class GLOccluderDepth : public testing::TestWithParam<bool> {};

TEST_P(GLOccluderDepth, NearestOfTrianglesAndStartDepthMatchesRayCasts) {
  const bool withStartDepth = GetParam();
  const Camera camera = Camera::lookAt(80, 60, 45.0f, {0.3f, -6.0f, 1.0f}, {0, 0, 0}, {0, 0, 1});
  TriangleMesh mesh;
  mesh.vertices = {{-2.0f, -1.0f, -1.5f}, {2.1f, 1.5f, -1.2f},  {0.2f, 0.0f, 2.0f},
                   {-1.8f, 1.2f, -1.0f},  {2.2f, -1.3f, -0.8f}, {-0.3f, 0.6f, 1.9f}};
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
  std::vector<float> start(std::size_t(camera.width) * camera.height, 1e10f);
  if (withStartDepth)
    for (int row = 0; row < camera.height; ++row)
      for (int column = 0; column < camera.width / 3; ++column)
        start[std::size_t(row) * camera.width + column] = 5.5f;
  PrepassHarness harness;
  // A wall near the camera first: the frame after it must not keep its depth.
  TriangleMesh nearWall;
  nearWall.vertices = {{-9, -5, -9}, {9, -5, -9}, {9, -5, 9}, {-9, -5, 9}};
  nearWall.triangles = {{0, 1, 2}, {0, 2, 3}};
  harness.run(camera, {&nearWall}, withStartDepth ? &start : nullptr);
  const std::vector<float> depth = harness.run(camera, {&mesh}, withStartDepth ? &start : nullptr);
  int compared = 0, covered = 0;
  for (int row = 0; row < camera.height; ++row) {
    for (int column = 0; column < camera.width; ++column) {
      const std::size_t index = std::size_t(row) * camera.width + column;
      double nearest = start[index];
      bool ambiguous = false;
      for (const glm::uvec3& triangle : mesh.triangles) {
        const glm::vec3 corners[3] = {mesh.vertices[triangle.x], mesh.vertices[triangle.y],
                                      mesh.vertices[triangle.z]};
        const double hit = referenceDepth(camera, corners, column, row, 0.01);
        const double loose = referenceDepth(camera, corners, column, row, 0.0);
        if (std::isnan(hit) != std::isnan(loose)) ambiguous = true;
        if (!std::isnan(hit)) nearest = std::min(nearest, hit);
      }
      if (ambiguous) continue;
      ++compared;
      covered += nearest < 1e9;
      EXPECT_NEAR(depth[index], nearest, 1e-5 * nearest) << "pixel " << column << ", " << row;
      ASSERT_TRUE(std::isfinite(depth[index]));
    }
  }
  EXPECT_GT(compared, camera.width * camera.height * 9 / 10);
  EXPECT_GT(covered, 800);
}

INSTANTIATE_TEST_SUITE_P(StartDepth, GLOccluderDepth, testing::Bool(),
                         [](const testing::TestParamInfo<bool>& info) {
                           return info.param ? "Given" : "None";
                         });

TEST(GLOccluderDepthEdges, NoTrianglesLeavesNothingOrTheStartDepth) {
  const Camera camera = Camera::lookAt(16, 12, 45.0f, {0, -6, 0}, {0, 0, 0}, {0, 0, 1});
  PrepassHarness harness;
  const TriangleMesh empty;
  for (float value : harness.run(camera, {&empty}, nullptr))
    ASSERT_EQ(value, 1e10f);
  const std::vector<float> start(16 * 12, 3.0f);
  EXPECT_EQ(harness.run(camera, {}, &start), start);
}

// A scene file's occluders: an OBJ wall between the camera and a liquid sphere hides all of the liquid, and
// a wall behind it hides nothing.
TEST(SceneOccluders, AnObjWallInFrontHidesTheLiquidFromTheSceneFile) {
  TempDirectory directory;
  directory.write("wall.obj", "v -10 0 -10\nv 10 0 -10\nv 10 0 10\nv -10 0 10\nf 1 2 3 4\n");
  directory.write(
      "particle.ply",
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
      "end_header\n0 0 0\n");
  auto sceneWithWallAt = [&](float y) {
    const std::string matrix = "[1,0,0,0, 0,1,0," + std::to_string(y) + ", 0,0,1,0, 0,0,0,1]";
    return directory.write("scene.json",
                           R"({"version": 1, "camera": {"width": 32, "height": 24, "fov_y_deg": 40,
                               "position": [0, -5, 0], "target": [0, 0, 0], "up": [0, 0, 1]},
                               "particles": [{"path": "particle.ply", "radius": 0.8}],
                               "occluders": [{"path": "wall.obj", "world_from_file": )" +
                               matrix + "}]}");
  };
  Renderer renderer;
  auto liquidPixels = [&](const RenderResult& result) {
    std::size_t count = 0;
    const ImageLayer& liquid = *result.layer("liquid");
    for (std::size_t i = 3; i < liquid.pixels.size(); i += 4)
      count += liquid.pixels[i] > 0.0f;
    return count;
  };
  const RenderResult behind = renderer.renderFrame(loadScene(sceneWithWallAt(2.0f)), 1);
  EXPECT_GT(liquidPixels(behind), 50u);
  const RenderResult inFront = renderer.renderFrame(loadScene(sceneWithWallAt(-2.0f)), 1);
  EXPECT_EQ(liquidPixels(inFront), 0u);
}

TEST(SceneOccluders, MeshKeysAreValidated) {
  TempDirectory directory;
  directory.write("wall.ply", "ply\n");
  const std::string camera = R"("camera": {"width": 8, "height": 8, "fov_y_deg": 40, "position": [0, -5, 0],
                                "target": [0, 0, 0], "up": [0, 0, 1]}, "particles": [])";
  auto message = [&](const std::string& extra) {
    try {
      parseScene("{\"version\": 1, " + camera + ", " + extra + "}", directory.path() / "scene.json");
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(
      message(R"("occluders": [{"path": "wall.ply"}])").find("occluders[0].path: expected a Wavefront .obj"),
      std::string::npos);
  EXPECT_NE(message(R"("occluders": [{"path": "missing.obj"}])").find("no such file"), std::string::npos);
  EXPECT_NE(message(R"("liquid_mesh": {"path": "x.obj", "scale": 2})").find("liquid_mesh"),
            std::string::npos);
  EXPECT_NE(message(R"("occluders": {"path": "x.obj"})").find("expected a list of meshes"),
            std::string::npos);
}

}  // namespace
