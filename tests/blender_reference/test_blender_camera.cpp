#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "BlenderReference.h"
#include "spindrift/Camera.h"

namespace spindrift {
namespace {

using test::blenderReference;

Camera referenceCamera() {
  const nlohmann::json& reference = blenderReference().at("camera");
  EXPECT_EQ(reference.at("sensor_fit"), "VERTICAL");
  Camera camera;
  camera.width = reference.at("width");
  camera.height = reference.at("height");
  camera.fovYDegrees = reference.at("angle_y_degrees").get<float>();
  camera.worldFromCamera = test::matrixFromRows(reference.at("matrix_world"));
  return camera;
}

TEST(BlenderCamera, ReferenceSeparatesPlanarDepthFromDistance) {
  // Were depth and distance to the camera alike for every point, the depth comparison below could not tell
  // planar depth from distance.
  double largestGap = 0.0;
  for (const nlohmann::json& point : blenderReference().at("camera").at("points")) {
    largestGap = std::max(largestGap, point.at("distance").get<double>() - point.at("depth").get<double>());
  }
  EXPECT_GT(largestGap, 0.1);
}

TEST(BlenderCamera, PixelAndDepthMatchBlenderWorldToCameraView) {
  const Camera camera = referenceCamera();
  int inside = 0;
  for (const nlohmann::json& point : blenderReference().at("camera").at("points")) {
    const glm::vec3 world = test::vec3(point.at("world"));
    const float expectedX = point.at("pixel").at(0);
    const float expectedY = point.at("pixel").at(1);
    const float expectedDepth = point.at("depth");
    const glm::vec3 projected = camera.pixelAndDepthFromWorld(world);
    SCOPED_TRACE(point.dump());
    EXPECT_NEAR(projected.x, expectedX, 1e-3);
    EXPECT_NEAR(projected.y, expectedY, 1e-3);
    EXPECT_NEAR(projected.z, expectedDepth, 1e-4 * expectedDepth);
    if (expectedX >= 0 && expectedX < camera.width && expectedY >= 0 && expectedY < camera.height) ++inside;
  }
  // Points on screen and off it both count: the mapping must hold for both.
  EXPECT_GE(inside, 5);
}

TEST(BlenderCamera, WorldFromPixelAndDepthInvertsBlenderProjection) {
  const Camera camera = referenceCamera();
  for (const nlohmann::json& point : blenderReference().at("camera").at("points")) {
    const glm::vec3 world = test::vec3(point.at("world"));
    const glm::vec2 pixel{point.at("pixel").at(0).get<float>(), point.at("pixel").at(1).get<float>()};
    const float depth = point.at("depth");
    SCOPED_TRACE(point.dump());
    EXPECT_LT(glm::distance(camera.worldFromPixelAndDepth(pixel, depth), world), 1e-4f * depth);
  }
}

}  // namespace
}  // namespace spindrift
