// The rectangle the impostor pass's normal resolve is limited to (prep/WindowRectangle.h) holds every pixel
// of every ellipsoid's bounding sphere: points all over each sphere, projected by the camera's own
// pixelAndDepthFromWorld, fall inside it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "prep/WindowRectangle.h"

using namespace spindrift;

namespace {

EllipsoidInstance sphere(const glm::vec3& centre, float radius) {
  EllipsoidInstance ellipsoid{};
  ellipsoid.centreAndBoundingRadius = glm::vec4(centre, radius);
  for (int row = 0; row < 3; ++row) {
    ellipsoid.inverseAxesRows[row] = glm::vec4(0.0f);
    ellipsoid.inverseAxesRows[row][row] = 1.0f / radius;
  }
  return ellipsoid;
}

Camera obliqueCamera() {
  return Camera::lookAt(160, 120, 40.0f, {3.0f, -4.0f, 2.5f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
}

bool inside(const WindowRectangle& rectangle, const glm::vec2& window) {
  return window.x >= float(rectangle.x) && window.x <= float(rectangle.x + rectangle.width) &&
         window.y >= float(rectangle.y) && window.y <= float(rectangle.y + rectangle.height);
}

}  // namespace

// Points all over a sphere, in GL window coordinates (from the bottom left).
std::vector<glm::vec2> windowPointsOf(const EllipsoidInstance& ellipsoid, const Camera& camera,
                                      std::mt19937& random) {
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<glm::vec2> points;
  const glm::vec3 centre(ellipsoid.centreAndBoundingRadius);
  while (points.size() < 400) {
    const glm::vec3 direction(unit(random), unit(random), unit(random));
    if (glm::length(direction) < 1e-3f) continue;
    const glm::vec3 pixel = camera.pixelAndDepthFromWorld(centre + ellipsoid.centreAndBoundingRadius.w *
                                                                       glm::normalize(direction));
    points.push_back({pixel.x, float(camera.height) - pixel.y});  // pixelAndDepthFromWorld counts y down
  }
  return points;
}

TEST(WindowRectangle, HoldsEveryPointOfEverySphere) {
  const Camera camera = obliqueCamera();
  std::mt19937 random(7);
  std::uniform_real_distribution<float> offset(-0.6f, 0.6f), size(0.02f, 0.15f);
  std::vector<EllipsoidInstance> spheres;
  for (int i = 0; i < 200; ++i)
    spheres.push_back(sphere({offset(random) + 0.4f, offset(random), offset(random) * 0.3f}, size(random)));
  const WindowRectangle cluster = windowRectangleOfSpheres(spheres, camera);
  // A cluster in part of the view: the rectangle is a part too, so the test says something about its edges.
  EXPECT_LT(cluster.pixels(), (long long)camera.width * camera.height / 2);
  std::size_t outside = 0, outsideOwn = 0, points = 0;
  long long ownPixels = 0;
  for (const EllipsoidInstance& ellipsoid : spheres) {
    // Each sphere alone too: its rectangle is within a pixel or two of its outline.
    const WindowRectangle own = windowRectangleOfSpheres({ellipsoid}, camera);
    ownPixels += own.pixels();
    for (const glm::vec2& point : windowPointsOf(ellipsoid, camera, random)) {
      ++points;
      outside += !inside(cluster, point);
      outsideOwn += !inside(own, point);
    }
  }
  EXPECT_EQ(points, 80000u);
  EXPECT_EQ(outside, 0u);
  EXPECT_EQ(outsideOwn, 0u);
  EXPECT_GT(ownPixels, 0);
}

TEST(WindowRectangle, NoEllipsoidsIsEmptyAndTheNearPlaneOrNaNTakesTheWholeView) {
  const Camera camera = obliqueCamera();
  EXPECT_EQ(windowRectangleOfSpheres({}, camera).pixels(), 0);
  const WindowRectangle whole{0, 0, camera.width, camera.height};
  const auto isWhole = [&](const WindowRectangle& r) {
    return r.x == whole.x && r.y == whole.y && r.width == whole.width && r.height == whole.height;
  };
  // A sphere around the camera reaches the near plane.
  EXPECT_TRUE(isWhole(windowRectangleOfSpheres({sphere(camera.position(), 0.5f)}, camera)));
  // Behind the camera: nothing is drawn there, but the rule stays conservative.
  EXPECT_TRUE(isWhole(windowRectangleOfSpheres({sphere(camera.position() * 2.0f, 0.1f)}, camera)));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(isWhole(
      windowRectangleOfSpheres({sphere({0.0f, 0.0f, 0.0f}, 0.1f), sphere({nan, 0.0f, 0.0f}, 0.1f)}, camera)));
  // A sphere partly off the view is clipped to it.
  const WindowRectangle clipped = windowRectangleOfSpheres({sphere({0.0f, 0.0f, 0.0f}, 3.0f)}, camera);
  EXPECT_GE(clipped.x, 0);
  EXPECT_GE(clipped.y, 0);
  EXPECT_LE(clipped.x + clipped.width, camera.width);
  EXPECT_LE(clipped.y + clipped.height, camera.height);
}
