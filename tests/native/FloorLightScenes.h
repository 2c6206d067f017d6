#pragma once

// Shared pieces of the GL tests of light through the liquid: the camera looks straight down at a floor
// (z = 0), so a floor pixel's position is known exactly and its background depth is the camera height.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

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

// A floor as Blender writes it with Cycles' light passes: Combined, Depth and constant DiffDir, DiffInd,
// DiffCol, GlossDir, GlossInd, GlossCol (Combined = DiffCol (DiffDir + DiffInd) + GlossCol (GlossDir +
// GlossInd)).
inline void writeFloorWithLightPasses(const std::filesystem::path& path, float eyeDepth,
                                      const float passes[6][3]) {
  const char* names[6] = {"DiffDir", "DiffInd", "DiffCol", "GlossDir", "GlossInd", "GlossCol"};
  std::vector<std::string> channels = {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B",
                                       "ViewLayer.Combined.A", "ViewLayer.Depth.Z"};
  for (const char* name : names)
    for (const char* channel : {"R", "G", "B"})
      channels.push_back(std::string("ViewLayer.") + name + "." + channel);
  const int count = int(channels.size());
  std::vector<float> pixels(std::size_t(kWidth) * kHeight * count);
  for (std::size_t pixel = 0; pixel < std::size_t(kWidth) * kHeight; ++pixel) {
    float* value = &pixels[pixel * count];
    for (int c = 0; c < 3; ++c)
      value[c] = passes[2][c] * (passes[0][c] + passes[1][c]) + passes[5][c] * (passes[3][c] + passes[4][c]);
    value[3] = 1.0f;
    value[4] = eyeDepth;
    for (int pass = 0; pass < 6; ++pass)
      for (int c = 0; c < 3; ++c)
        value[5 + 3 * pass + c] = passes[pass][c];
  }
  auto output = OIIO::ImageOutput::create(path.string());
  OIIO::ImageSpec spec(kWidth, kHeight, count, OIIO::TypeDesc::FLOAT);
  spec.channelnames = channels;
  output->open(path.string(), spec);
  output->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
  output->close();
}

}  // namespace floor_light
