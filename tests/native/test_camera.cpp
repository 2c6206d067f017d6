#include <gtest/gtest.h>

#include <glm/gtc/matrix_access.hpp>

#include "spindrift/Camera.h"

using namespace spindrift;

// Blender's convention, checked by hand: a camera at the origin with identity matrix looks down -Z with +Y
// up, so a point straight ahead at depth 5 lands in the image centre at planar depth 5.
TEST(Camera, IdentityLooksDownMinusZ) {
  Camera camera;
  camera.width = 200;
  camera.height = 100;
  camera.fovYDegrees = 90.0f;
  const glm::vec3 centre = camera.pixelAndDepthFromWorld({0, 0, -5});
  EXPECT_NEAR(centre.x, 100.0f, 1e-4f);
  EXPECT_NEAR(centre.y, 50.0f, 1e-4f);
  EXPECT_NEAR(centre.z, 5.0f, 1e-6f);
  // With a 90 degree vertical field of view, y = depth is the top edge (pixel row 0), and x = depth * aspect
  // the right edge.
  EXPECT_NEAR(camera.pixelAndDepthFromWorld({0, 5, -5}).y, 0.0f, 1e-4f);
  EXPECT_NEAR(camera.pixelAndDepthFromWorld({10, 0, -5}).x, 200.0f, 1e-4f);
}

TEST(Camera, DepthIsPlanarNotRadial) {
  Camera camera;
  camera.width = camera.height = 64;
  camera.fovYDegrees = 60.0f;
  EXPECT_NEAR(camera.pixelAndDepthFromWorld({2, 1, -3}).z, 3.0f, 1e-6f);
}

TEST(Camera, PixelAndDepthRoundTrip) {
  const Camera camera = Camera::lookAt(320, 180, 35.0f, {3, -7, 2}, {0, 0, 0.5f}, {0, 0, 1});
  for (const glm::vec3 world : {glm::vec3(0, 0, 0), glm::vec3(1, 2, 0.3f), glm::vec3(-1, 1, 1)}) {
    const glm::vec3 pixelAndDepth = camera.pixelAndDepthFromWorld(world);
    const glm::vec3 back = camera.worldFromPixelAndDepth(glm::vec2(pixelAndDepth), pixelAndDepth.z);
    EXPECT_NEAR(glm::distance(back, world), 0.0f, 1e-5f);
  }
}

TEST(Camera, ClipMatrixAgreesWithPixelMapping) {
  const Camera camera = Camera::lookAt(320, 180, 35.0f, {3, -7, 2}, {0, 0, 0.5f}, {0, 0, 1});
  const glm::vec3 world(0.4f, 0.2f, 0.9f);
  const glm::vec4 clip = camera.clipFromWorld() * glm::vec4(world, 1.0f);
  const glm::vec3 pixel = camera.pixelAndDepthFromWorld(world);
  EXPECT_NEAR((clip.x / clip.w * 0.5f + 0.5f) * 320.0f, pixel.x, 1e-3f);
  EXPECT_NEAR((0.5f - clip.y / clip.w * 0.5f) * 180.0f, pixel.y, 1e-3f);
  EXPECT_NEAR(clip.w, pixel.z, 1e-5f);
}

TEST(Camera, LookAtPutsTargetInTheCentreWithUpUp) {
  const Camera camera = Camera::lookAt(100, 100, 50.0f, {0, -10, 0}, {0, 0, 0}, {0, 0, 1});
  const glm::vec3 target = camera.pixelAndDepthFromWorld({0, 0, 0});
  EXPECT_NEAR(target.x, 50.0f, 1e-4f);
  EXPECT_NEAR(target.y, 50.0f, 1e-4f);
  EXPECT_LT(camera.pixelAndDepthFromWorld({0, 0, 1}).y, 50.0f) << "world up must be image up";
}
