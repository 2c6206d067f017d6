#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "BlenderReference.h"
#include "io/ParticleFile.h"

namespace spindrift {
namespace {

using nlohmann::json;
using test::blenderReference;

/// The mapping of docs/mantaflow-caches.md from a Mantaflow cache's point positions to Blender's world space,
/// computed from the domain object alone (matrix_world, scale, the mesh's bound box) and resolution_max.
struct DomainGrid {
  glm::ivec3 resolution{0};
  float cellSize = 0.0f;  ///< In the cache's units (the domain's local frame times the object's scale).
  glm::vec3 localMin{0.0f};
  glm::vec3 localMax{0.0f};
  glm::mat4 worldFromFile{1.0f};
};

DomainGrid domainGrid(const json& domain, int resolutionMax) {
  DomainGrid grid;
  grid.localMin = glm::vec3(std::numeric_limits<float>::max());
  grid.localMax = -grid.localMin;
  for (const json& corner : domain.at("bound_box_local")) {
    grid.localMin = glm::min(grid.localMin, test::vec3(corner));
    grid.localMax = glm::max(grid.localMax, test::vec3(corner));
  }
  const glm::vec3 scale = glm::abs(test::vec3(domain.at("scale")));
  const glm::vec3 size = (grid.localMax - grid.localMin) * scale;
  const float longest = std::max({size.x, size.y, size.z});
  grid.cellSize = longest / float(resolutionMax);
  for (int axis = 0; axis < 3; ++axis) {
    grid.resolution[axis] = std::max(int(size[axis] * (float(resolutionMax) / longest) + 0.5f), 4);
  }
  // The grid is centred on the mesh's bound box and may overhang it by up to half a cell per side.
  const glm::vec3 centre = 0.5f * (grid.localMin + grid.localMax);
  const glm::vec3 gridMin = centre - glm::vec3(grid.resolution) * grid.cellSize / (2.0f * scale);
  grid.worldFromFile = test::matrixFromRows(domain.at("matrix_world")) *
                       glm::translate(glm::mat4(1.0f), gridMin) * glm::scale(glm::mat4(1.0f), 1.0f / scale);
  return grid;
}

std::vector<glm::vec3> toWorld(const DomainGrid& grid, const std::vector<glm::vec3>& filePositions) {
  std::vector<glm::vec3> world;
  world.reserve(filePositions.size());
  for (const glm::vec3& p : filePositions)
    world.emplace_back(grid.worldFromFile * glm::vec4(p, 1.0f));
  return world;
}

std::vector<glm::vec3> points(const json& list) {
  std::vector<glm::vec3> result;
  for (const json& point : list)
    result.push_back(test::vec3(point));
  return result;
}

/// The largest distance from a point of `from` to its nearest neighbour in `to`.
float largestNearestDistance(const std::vector<glm::vec3>& from, const std::vector<glm::vec3>& to) {
  float largest = 0.0f;
  for (const glm::vec3& p : from) {
    float nearest = std::numeric_limits<float>::infinity();
    for (const glm::vec3& q : to)
      nearest = std::min(nearest, glm::distance(p, q));
    largest = std::max(largest, nearest);
  }
  return largest;
}

int resolutionMax() {
  return blenderReference().at("fluid").at("resolution_max");
}
const json& domains() {
  return blenderReference().at("fluid").at("domains");
}

const std::map<std::string, int> kKindFlags = {{"spray", 2}, {"bubble", 4}, {"foam", 8}};

TEST(MantaflowCache, GridResolutionMatchesBlender) {
  for (const json& domain : domains()) {
    SCOPED_TRACE(domain.at("name").get<std::string>());
    const DomainGrid grid = domainGrid(domain, resolutionMax());
    const json& blender = domain.at("domain_resolution");
    EXPECT_EQ(grid.resolution, glm::ivec3(blender.at(0), blender.at(1), blender.at(2)));
  }
}

TEST(MantaflowCache, LiquidCountsMatchBlender) {
  for (const json& domain : domains()) {
    for (const auto& [frame, record] : domain.at("frames").items()) {
      SCOPED_TRACE(domain.at("name").get<std::string>() + " frame " + frame);
      const ParticleFileData data = readVdbPoints(record.at("files").at("liquid").get<std::string>(), "");
      EXPECT_EQ(data.positions.size(), record.at("counts").at("liquid").get<std::size_t>());
      EXPECT_EQ(data.velocities.size(), data.positions.size());
      // The liquid's U is Mantaflow's particle flag, not a kind: 0, or 1 for particles new this step.
      EXPECT_EQ(data.typeFlags.size(), data.positions.size());
      for (std::int32_t flag : data.typeFlags)
        EXPECT_TRUE(flag == 0 || flag == 1) << flag;
      EXPECT_TRUE(data.life.empty());
      EXPECT_TRUE(data.radii.empty());
    }
  }
}

TEST(MantaflowCache, SecondaryFlagsAndCountsMatchBlender) {
  bool sawParticles = false;
  for (const json& domain : domains()) {
    for (const auto& [frame, record] : domain.at("frames").items()) {
      SCOPED_TRACE(domain.at("name").get<std::string>() + " frame " + frame);
      const ParticleFileData data = readVdbPoints(record.at("files").at("secondary").get<std::string>(), "");
      ASSERT_EQ(data.typeFlags.size(), data.positions.size());
      ASSERT_EQ(data.life.size(), data.positions.size());
      ASSERT_EQ(data.velocities.size(), data.positions.size());
      std::map<int, std::size_t> perFlag;
      for (std::int32_t flag : data.typeFlags)
        ++perFlag[flag];
      for (const auto& [kind, flag] : kKindFlags) {
        EXPECT_EQ(perFlag[flag], record.at("counts").at(kind).get<std::size_t>()) << kind;
        perFlag.erase(flag);
      }
      EXPECT_TRUE(perFlag.empty()) << "flags other than 2, 4, 8: " << perFlag.begin()->first;
      for (float life : data.life)
        EXPECT_TRUE(std::isfinite(life) && life >= 0.0f) << life;
      sawParticles = sawParticles || !data.positions.empty();
    }
  }
  EXPECT_TRUE(sawParticles) << "the fixture should have secondary particles at its reference frame";
}

TEST(MantaflowCache, LiquidWorldPositionsMatchBlender) {
  for (const json& domain : domains()) {
    if (!domain.at("blender_positions_reliable").get<bool>()) continue;
    const DomainGrid grid = domainGrid(domain, resolutionMax());
    for (const auto& [frame, record] : domain.at("frames").items()) {
      SCOPED_TRACE(domain.at("name").get<std::string>() + " frame " + frame);
      const std::vector<glm::vec3> ours =
          toWorld(grid, readVdbPoints(record.at("files").at("liquid").get<std::string>(), "").positions);
      const std::vector<glm::vec3> blender = points(record.at("positions_world").at("liquid"));
      ASSERT_EQ(ours.size(), blender.size());
      // Blender's positions are rounded to 1e-6 in the JSON; a wrong mapping is off by a good part of a cell.
      EXPECT_LT(largestNearestDistance(ours, blender), 1e-4f);
      EXPECT_LT(largestNearestDistance(blender, ours), 1e-4f);
    }
  }
}

TEST(MantaflowCache, SecondaryWorldPositionsMatchBlenderPerKind) {
  for (const json& domain : domains()) {
    if (!domain.at("blender_positions_reliable").get<bool>()) continue;
    const DomainGrid grid = domainGrid(domain, resolutionMax());
    const json& record = domain.at("frames").at(
        std::to_string(blenderReference().at("fluid").at("reference_frame").get<int>()));
    const ParticleFileData data = readVdbPoints(record.at("files").at("secondary").get<std::string>(), "");
    const std::vector<glm::vec3> world = toWorld(grid, data.positions);
    for (const auto& [kind, flag] : kKindFlags) {
      SCOPED_TRACE(domain.at("name").get<std::string>() + " " + kind);
      std::vector<glm::vec3> ours;
      for (std::size_t i = 0; i < world.size(); ++i) {
        if (data.typeFlags[i] == flag) ours.push_back(world[i]);
      }
      const std::vector<glm::vec3> blender = points(record.at("positions_world").at(kind));
      ASSERT_EQ(ours.size(), blender.size());
      ASSERT_FALSE(ours.empty());
      EXPECT_LT(largestNearestDistance(ours, blender), 1e-4f);
      EXPECT_LT(largestNearestDistance(blender, ours), 1e-4f);
    }
  }
}

TEST(MantaflowCache, WorldPositionsLieInsideTheDomain) {
  for (const json& domain : domains()) {
    const DomainGrid grid = domainGrid(domain, resolutionMax());
    const glm::mat4 localFromWorld = glm::inverse(test::matrixFromRows(domain.at("matrix_world")));
    // The grid overhangs the mesh by at most half a cell per side.
    const glm::vec3 slack = 0.5f * grid.cellSize / glm::abs(test::vec3(domain.at("scale"))) + 1e-5f;
    for (const auto& [frame, record] : domain.at("frames").items()) {
      for (const char* file : {"liquid", "secondary"}) {
        SCOPED_TRACE(domain.at("name").get<std::string>() + " frame " + frame + " " + file);
        const auto data = readVdbPoints(record.at("files").at(file).get<std::string>(), "");
        for (const glm::vec3& world : toWorld(grid, data.positions)) {
          const glm::vec3 local(localFromWorld * glm::vec4(world, 1.0f));
          ASSERT_TRUE(glm::all(glm::greaterThanEqual(local, grid.localMin - slack)) &&
                      glm::all(glm::lessThanEqual(local, grid.localMax + slack)))
              << local.x << ' ' << local.y << ' ' << local.z;
        }
      }
    }
  }
}

TEST(MantaflowCache, FreshlyEmittedLiquidFillsItsEmitter) {
  // A check of the mapping that needs no Blender particle display: on the first frame the liquid still fills
  // the sphere that emitted it. It covers the off-centre domain, whose Blender particle display is shifted.
  const std::string emissionFrame =
      std::to_string(blenderReference().at("fluid").at("emission_frame").get<int>());
  for (const json& domain : domains()) {
    SCOPED_TRACE(domain.at("name").get<std::string>());
    const DomainGrid grid = domainGrid(domain, resolutionMax());
    const json& record = domain.at("frames").at(emissionFrame);
    const std::vector<glm::vec3> world =
        toWorld(grid, readVdbPoints(record.at("files").at("liquid").get<std::string>(), "").positions);
    ASSERT_GT(world.size(), 100u);
    const glm::vec3 centre = test::vec3(domain.at("flow_sphere").at("center_world"));
    const float radius = domain.at("flow_sphere").at("radius");
    glm::vec3 sum(0.0f);
    for (const glm::vec3& p : world) {
      EXPECT_LT(glm::distance(p, centre), radius + 0.5f * grid.cellSize);
      sum += p;
    }
    EXPECT_LT(glm::distance(sum / float(world.size()), centre), 0.3f * grid.cellSize);
  }
}

}  // namespace
}  // namespace spindrift
