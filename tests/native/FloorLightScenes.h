#pragma once

// Shared pieces of the GL tests of light through the liquid: the camera looks straight down at a floor
// (z = 0), so a floor pixel's position is known exactly and its background depth is the camera height.
#include <cmath>
#include <string>
#include <utility>

#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>

#include "BackgroundFiles.h"
#include "LiquidTestScenes.h"
#include "TempDirectory.h"

namespace floor_light {

using namespace spindrift;
using liquid_test::at;

inline constexpr int kWidth = 160, kHeight = 120;
inline constexpr float kCameraHeight = 6.0f;
inline constexpr float kFovY = 40.0f;

// The floor's size on the screen: world units per pixel.
inline double floorPixelSize(double cameraHeight = kCameraHeight) {
  return 2.0 * cameraHeight * std::tan(glm::radians(kFovY * 0.5)) / kHeight;
}

// World (x, y) of a floor pixel's centre (row 0 at the top; +y up the image).
inline glm::dvec2 floorPoint(int column, int row, double cameraHeight = kCameraHeight) {
  const double pixel = floorPixelSize(cameraHeight);
  return {(column + 0.5 - kWidth * 0.5) * pixel, (kHeight * 0.5 - row - 0.5) * pixel};
}

inline Scene floorScene(const TempDirectory& directory, float cameraHeight = kCameraHeight) {
  Scene scene;
  scene.camera = Camera::lookAt(kWidth, kHeight, kFovY, {0.0f, 0.0f, cameraHeight}, {0.0f, 0.0f, 0.0f},
                                {0.0f, 1.0f, 0.0f});
  scene.background.image = directory.path() / "floor.exr";
  writeBackgroundExr(
      scene.background.image, kWidth, kHeight, [](int, int) { return glm::vec3(0.5f); },
      [cameraHeight](int, int) { return cameraHeight; });
  return scene;
}

inline Light sunAlong(const glm::vec3& direction, float strength = 3.0f) {
  Light sun;
  sun.type = Light::Type::Sun;
  sun.direction = glm::normalize(direction);
  sun.strength = strength;
  return sun;
}

// The direct-light multiplier of a floor pixel: what the liquid leaves of the light plus what it refracts.
inline double directMultiplier(const RenderResult& result, int column, int row, int channel) {
  return at(*result.layer("liquid_shadow"), kWidth, column, row, channel) +
         at(*result.layer("caustics"), kWidth, column, row, channel);
}

// A slab of water, the lattice of particles filling [low, high] with overlapping spheres.
inline Particles slabParticles(const glm::vec3& low, const glm::vec3& high) {
  return liquid_test::particlesOf(liquid_test::block(low, high, 0.05f), 0.05f);
}

// The drawn slab's top and bottom heights: its top measured by the camera's depth layer at the image centre,
// its bottom the mirror image of the top about the lattice's middle plane (the lattice is symmetric), so the
// light's optics are checked against the drawn geometry.
inline std::pair<double, double> slabTopAndBottom(const RenderResult& result, float cameraHeight,
                                                  double middle) {
  const double top = cameraHeight - at(*result.layer("depth"), kWidth, kWidth / 2, kHeight / 2, 0);
  return {top, 2.0 * middle - top};
}

inline bool skipped(const RenderResult& result, const std::string& pass, std::string* reason = nullptr) {
  for (const SkippedPass& skip : result.stats.skipped)
    if (skip.name == pass) {
      if (reason) *reason = skip.reason;
      return true;
    }
  return false;
}

}  // namespace floor_light
