// The ray-marched surface's binary density grid on real Mantaflow particles (the fixture's tiny bake): no
// cell the GPU marks empty may hold density at or above the iso-value (brute-force CPU check,
// RaymarchGridCheck.h).
#include <gtest/gtest.h>

#include <algorithm>

#include "../native/RaymarchGridCheck.h"
#include "BlenderReference.h"
#include "io/ParticleFile.h"

namespace spindrift {
namespace {

// The domain's cell size in the cache's units: its longest side over the longest resolution. Mantaflow seeds
// two particles per cell along each axis, so the particle spacing, and Spindrift's radius, is half of it.
float cacheCellSize(const nlohmann::json& domain) {
  glm::vec3 low(INFINITY), high(-INFINITY);
  for (const nlohmann::json& corner : domain.at("bound_box_local")) {
    low = glm::min(low, test::vec3(corner));
    high = glm::max(high, test::vec3(corner));
  }
  const glm::vec3 size = (high - low) * glm::abs(test::vec3(domain.at("scale")));
  const nlohmann::json& resolution = domain.at("domain_resolution");
  const int longest =
      std::max({resolution.at(0).get<int>(), resolution.at(1).get<int>(), resolution.at(2).get<int>()});
  return std::max({size.x, size.y, size.z}) / float(longest);
}

TEST(RaymarchMantaflow, DensityGridIsConservative) {
  std::size_t frames = 0;
  for (const nlohmann::json& domain : test::blenderReference().at("fluid").at("domains")) {
    const float radius = 0.5f * cacheCellSize(domain);
    // The fixture's frames: the first emission, and a later one with sheets and droplets.
    for (const auto& [frame, record] : domain.at("frames").items()) {
      SCOPED_TRACE(domain.at("name").get<std::string>() + " frame " + frame);
      const ParticleFileData data = readVdbPoints(record.at("files").at("liquid").get<std::string>(), "");
      if (data.positions.empty()) continue;
      // Supports vary per particle as the derived surface sizes them (docs/raymarch.md): the base h, and
      // every third particle a splash-sized 2.5 h, which sets the cells.
      LiquidParameters parameters;
      const float h = parameters.raymarch_smoothing_radius * radius;
      std::vector<glm::vec4> particles;
      for (std::size_t i = 0; i < data.positions.size(); ++i)
        particles.emplace_back(data.positions[i], i % 3 == 0 ? 2.5f * h : h);
      const raymarch_test::GridCheck check = raymarch_test::checkDensityGrid(particles, parameters);
      EXPECT_GT(check.crossingCells, 0u);
      EXPECT_LT(check.markedCells, check.cells);
      EXPECT_EQ(check.missedCells, 0u) << "cells marked 0 that hold density at or above the iso-value";
      ++frames;
    }
  }
  EXPECT_GT(frames, 0u);
}

}  // namespace
}  // namespace spindrift
