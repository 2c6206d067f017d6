// Liquid pressed against the walls of its Mantaflow domain (docs/mantaflow-caches.md, "The liquid mesh"):
// Mantaflow closes its mesh there with a flat face, and Spindrift clips the grown particles to the domain's
// box. Seen from outside, the face must be flat, closed and lit with the wall's normal: depth against the
// analytic plane, normals against the wall's, coverage without holes, every channel finite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_access.hpp>
#include <glm/trigonometric.hpp>

#include "LiquidTestScenes.h"
#include "spindrift/Scene.h"

namespace spindrift {
namespace {

using liquid_test::at;

constexpr float kSpacing = 0.1f;
constexpr float kRadius = 0.11f;
constexpr float kWall = 1.95f;  // the box's face at +x (and +y), inset from the domain's side at 2

// A pool filling a box domain [0, 2]^3 up to z = 1, particles half a spacing from the sides, grown by one
// radius as a Mantaflow domain's surface offset grows them; the box clips them at 0.05 inside the sides.
Scene poolScene(const glm::vec3& cameraPosition, const glm::vec3& target, bool clip) {
  Scene scene;
  scene.camera = Camera::lookAt(128, 96, 40.0f, cameraPosition, target, {0, 0, 1});
  scene.background.color = {0.4f, 0.5f, 0.6f};
  scene.parameters.liquid.surface_offset = 1.0f;
  ParticleSource source;
  source.radius = kRadius;
  if (clip) source.domainBox = DomainBox{glm::mat4(1.0f), glm::vec3(2.0f - kWall), glm::vec3(kWall)};
  scene.particles.push_back(source);
  return scene;
}

Particles pool() {
  return liquid_test::particlesOf(liquid_test::block({0.05f, 0.05f, 0.05f}, {1.95f, 1.95f, 0.95f}, kSpacing),
                                  kRadius);
}

struct FaceErrors {
  int facePixels = 0;
  int holes = 0;                   // face pixels the liquid does not cover
  float largestDepthError = 0.0f;  // in radii
  float largestNormalDegrees = 0.0f;
};

// Over the pixels whose ray meets the plane x = kWall well inside the face (y and z at least 0.25 from its
// edges), the liquid's depth and normal against the plane's.
FaceErrors wallFaceErrors(const Scene& scene, const RenderResult& result) {
  const Camera& camera = scene.camera;
  const ImageLayer& depth = *result.layer("depth");
  const ImageLayer& normal = *result.layer("normal");
  const glm::vec3 position(glm::column(camera.worldFromCamera, 3));
  const float focal = 1.0f / std::tan(glm::radians(camera.fovYDegrees) / 2.0f);
  FaceErrors errors;
  for (int row = 0; row < camera.height; ++row)
    for (int column = 0; column < camera.width; ++column) {
      const float x = (2.0f * (column + 0.5f) / camera.width - 1.0f) * float(camera.width) / camera.height;
      const float y = 1.0f - 2.0f * (row + 0.5f) / camera.height;
      const glm::vec3 cameraRay(x / focal, y / focal, -1.0f);  // planar depth 1 along it
      const glm::vec3 ray = glm::mat3(camera.worldFromCamera) * cameraRay;
      const float t = (kWall - position.x) / ray.x;
      const glm::vec3 hit = position + t * ray;
      if (!(t > 0.0f) || hit.y < 0.3f || hit.y > 1.7f || hit.z < 0.3f || hit.z > 0.7f) continue;
      ++errors.facePixels;
      const float liquidDepth = at(depth, camera.width, column, row, 0);
      if (liquidDepth > 1e9f) {
        ++errors.holes;
        continue;
      }
      errors.largestDepthError = std::max(errors.largestDepthError, std::abs(liquidDepth - t) / kRadius);
      const glm::vec3 n(at(normal, camera.width, column, row, 0), at(normal, camera.width, column, row, 1),
                        at(normal, camera.width, column, row, 2));
      const float cosine = glm::dot(glm::normalize(n), glm::vec3(1, 0, 0));
      errors.largestNormalDegrees =
          std::max(errors.largestNormalDegrees, glm::degrees(std::acos(std::clamp(cosine, -1.0f, 1.0f))));
    }
  return errors;
}

TEST(GLLiquidWalls, PoolAgainstTheDomainWallReadsAsAFlatClosedFace) {
  const Scene scene = poolScene({5.0f, 1.6f, 1.6f}, {kWall, 1.0f, 0.5f}, true);
  const RenderResult result = liquid_test::renderer().renderParticles(scene, pool(), 1);
  liquid_test::expectAllChannelsFinite(result);
  const FaceErrors errors = wallFaceErrors(scene, result);
  ASSERT_GT(errors.facePixels, 400);
  EXPECT_EQ(errors.holes, 0);
  EXPECT_LT(errors.largestDepthError, 0.05f);
  EXPECT_LT(errors.largestNormalDegrees, 2.0f);
}

TEST(GLLiquidWalls, WithoutTheDomainTheGrownParticlesBulgePastTheWall) {
  // The same pool without its box: the face is the particles' bumps, a radius or more off the plane, which
  // is what the clip removes (and shows the test above can fail).
  const Scene scene = poolScene({5.0f, 1.6f, 1.6f}, {kWall, 1.0f, 0.5f}, false);
  const RenderResult result = liquid_test::renderer().renderParticles(scene, pool(), 1);
  liquid_test::expectAllChannelsFinite(result);
  const FaceErrors errors = wallFaceErrors(scene, result);
  // Smoothing still makes that face look flat (its normals come from the smoothed depth); its place is wrong.
  EXPECT_GT(errors.largestDepthError, 0.5f);
}

TEST(GLLiquidWalls, CornerOfTheBoxSeenDiagonally) {
  // Two walls and the corner between them, seen at 45 degrees: finite everywhere, and the +x face still flat.
  const Scene scene = poolScene({5.0f, 5.0f, 2.5f}, {kWall, kWall, 0.5f}, true);
  const RenderResult result = liquid_test::renderer().renderParticles(scene, pool(), 1);
  liquid_test::expectAllChannelsFinite(result);
  const FaceErrors errors = wallFaceErrors(scene, result);
  ASSERT_GT(errors.facePixels, 100);
  EXPECT_EQ(errors.holes, 0);
  // Depth smoothing blends the two faces' normals over a few pixels next to the corner's edge (8.9 degrees
  // at worst, measured on llvmpipe), which the face region here reaches at this angle.
  EXPECT_LT(errors.largestNormalDegrees, 10.0f);
}

}  // namespace
}  // namespace spindrift
