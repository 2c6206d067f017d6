#pragma once

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "spindrift/Renderer.h"

// Shared pieces of the liquid GL tests: one renderer per test binary (contexts are slow on llvmpipe), scenes
// built in code, and the check that every channel of every layer is finite.
namespace liquid_test {

inline spindrift::Renderer& renderer() {
  static spindrift::Renderer instance;
  return instance;
}

inline spindrift::Particles particlesOf(const std::vector<glm::vec3>& positions, float radius) {
  spindrift::Particles particles;
  for (const glm::vec3& position : positions)
    particles.append(position, radius, spindrift::ParticleKind::Liquid, 0.0f, glm::vec3(0.0f));
  return particles;
}

// A wavy sheet of liquid `layers` particles thick, 0.8 m across, 0.02 apart with jitter (radius 0.02): its
// surface particles become flattened ellipsoids.
inline spindrift::Particles wavySheet(int layers, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> jitter(-0.004f, 0.004f);
  std::vector<glm::vec3> positions;
  const float spacing = 0.02f;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j)
      for (int k = 0; k < layers; ++k) {
        const float x = -0.4f + i * spacing, y = -0.4f + j * spacing;
        const float z = 0.05f * std::sin(6.0f * x) * std::cos(5.0f * y) + k * spacing;
        positions.emplace_back(x + jitter(random), y + jitter(random), z + jitter(random));
      }
  return particlesOf(positions, 0.02f);
}

// A regular block of particles, spacing `spacing`, filling [low, high].
inline std::vector<glm::vec3> block(const glm::vec3& low, const glm::vec3& high, float spacing) {
  std::vector<glm::vec3> positions;
  for (float z = low.z; z <= high.z + 1e-6f; z += spacing)
    for (float y = low.y; y <= high.y + 1e-6f; y += spacing)
      for (float x = low.x; x <= high.x + 1e-6f; x += spacing)
        positions.emplace_back(x, y, z);
  return positions;
}

// A ball of `radius` about `centre` filled with a regular lattice of particles `spacing` apart, the outermost
// reaching its surface.
inline spindrift::Particles latticeBall(const glm::vec3& centre, float radius, float spacing,
                                        float particleRadius) {
  std::vector<glm::vec3> inside;
  const float reach = radius - particleRadius;
  for (const glm::vec3& position : block(centre - glm::vec3(reach), centre + glm::vec3(reach), spacing))
    if (glm::distance(position, centre) <= reach) inside.push_back(position);
  return particlesOf(inside, particleRadius);
}

inline std::size_t nonFiniteValues(const spindrift::RenderResult& result, std::string* where = nullptr) {
  std::size_t bad = 0;
  for (const spindrift::ImageLayer& layer : result.layers)
    for (float value : layer.pixels)
      if (!std::isfinite(value)) {
        if (where && bad == 0) *where = layer.name;
        ++bad;
      }
  return bad;
}

inline void expectAllChannelsFinite(const spindrift::RenderResult& result) {
  std::string where;
  const std::size_t bad = nonFiniteValues(result, &where);
  EXPECT_EQ(bad, 0u) << "non-finite values, first in layer " << where;
  for (const char* layer : {"composite", "liquid", "liquid_splash", "liquid_class", "depth", "normal",
                            "thickness", "refraction_uv", "transmittance", "reflection"})
    EXPECT_NE(result.layer(layer), nullptr) << layer;
}

// Two renders hold the same layers, every value the same to the bit (a skipped pass changes nothing).
inline void expectSameLayers(const spindrift::RenderResult& expected, const spindrift::RenderResult& actual) {
  EXPECT_EQ(actual.layers.size(), expected.layers.size());
  for (const spindrift::ImageLayer& layer : expected.layers) {
    SCOPED_TRACE(layer.name);
    const spindrift::ImageLayer* other = actual.layer(layer.name);
    EXPECT_TRUE(other && other->pixels.size() == layer.pixels.size());
    if (other && other->pixels.size() == layer.pixels.size())
      EXPECT_EQ(std::memcmp(other->pixels.data(), layer.pixels.data(), layer.pixels.size() * sizeof(float)),
                0);
  }
}

inline float at(const spindrift::ImageLayer& layer, int width, int column, int row, int channel) {
  return layer.pixels[(std::size_t(row) * width + column) * layer.channelCount() + channel];
}

}  // namespace liquid_test
