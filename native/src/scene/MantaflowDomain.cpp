#include "scene/MantaflowDomain.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include <zlib.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "spindrift/Error.h"

namespace spindrift {
namespace {

// The config header as Blender 3.4's MANTA::writeConfiguration writes it, field by field (little-endian).
struct RawConfig {
  std::int32_t activeFields;
  std::int32_t resolution[3];
  float dx;
  float dt;
  float p0[3];
  float p1[3];
  float dp0[3];
  std::int32_t shift[3];
  float objectShift[3];
  float objectMatrix[16];  // column-major, as Blender stores obmat
};

// Weighted mean height of the particles around (x, y, h) with Mantaflow's averaged level set weight
// max(0, 1 - d^2 / (2 r)^2) (ComputeAveragedLevelsetWeight), or for the union level set the distance to the
// nearest particle; the particles sit on a lattice of `spacing` filling z < 0, the top layer at -spacing / 2.
float levelSetAbove(float x, float y, float h, float kernelRadius, float spacing, bool averaged) {
  const float support = 2.0f * kernelRadius;
  const int reach = int(std::ceil(support / spacing)) + 1;
  double weightSum = 0.0, sx = 0.0, sy = 0.0, sz = 0.0;
  float nearest = 1e30f;
  for (int k = 0; k < reach; ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const float px = i * spacing, py = j * spacing, pz = -(k + 0.5f) * spacing;
        const float d2 = (px - x) * (px - x) + (py - y) * (py - y) + (pz - h) * (pz - h);
        nearest = std::min(nearest, std::sqrt(d2));
        const float w = 1.0f - d2 / (support * support);
        if (w <= 0.0f) continue;
        weightSum += w;
        sx += w * px;
        sy += w * py;
        sz += w * pz;
      }
  if (!averaged) return nearest - kernelRadius;
  if (weightSum <= 0.0) return kernelRadius;
  const glm::vec3 mean(float(sx / weightSum), float(sy / weightSum), float(sz / weightSum));
  return glm::length(glm::vec3(x, y, h) - mean) - kernelRadius;
}

float flatOffset(float kernelRadius, float spacing, bool averaged) {
  // Averaged over a few places across the lattice, as the mesh grid's cell centres fall anywhere on it.
  const float places[3][2] = {{0.0f, 0.0f}, {0.25f, 0.25f}, {0.5f, 0.5f}};
  float sum = 0.0f;
  for (const auto& place : places) {
    float inside = -spacing, outside = 3.0f * kernelRadius + spacing;
    for (int step = 0; step < 40; ++step) {
      const float middle = 0.5f * (inside + outside);
      const bool isInside = levelSetAbove(place[0] * spacing, place[1] * spacing, middle, kernelRadius,
                                          spacing, averaged) < 0.0f;
      (isInside ? inside : outside) = middle;
    }
    sum += 0.5f * (inside + outside) + 0.5f * spacing;
  }
  return sum / 3.0f;
}

std::string formatNumber(float value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", double(value));
  return text;
}

}  // namespace

glm::vec3 MantaflowCacheConfig::objectScale() const {
  return glm::vec3(glm::length(glm::vec3(worldFromObject[0])), glm::length(glm::vec3(worldFromObject[1])),
                   glm::length(glm::vec3(worldFromObject[2])));
}

float MantaflowCacheConfig::cellSize() const {
  const glm::vec3 size = (boundsMax - boundsMin) * objectScale();
  return normalisedCellSize * std::max(size.x, std::max(size.y, size.z));
}

glm::mat4 MantaflowCacheConfig::worldFromFile() const {
  const glm::vec3 scale = objectScale();
  const glm::vec3 gridLow =
      0.5f * (boundsMin + boundsMax) - glm::vec3(resolution) * cellSize() / (2.0f * scale);
  return worldFromObject * glm::translate(glm::mat4(1.0f), gridLow) *
         glm::scale(glm::mat4(1.0f), 1.0f / scale);
}

MantaflowCacheConfig readMantaflowCacheConfig(const std::filesystem::path& path) {
  gzFile file = gzopen(path.string().c_str(), "rb");
  if (!file) throw Error(path.string() + ": cannot open the Mantaflow config file");
  RawConfig raw;
  const int read = gzread(file, &raw, sizeof raw);
  gzclose(file);
  if (read != int(sizeof raw)) throw Error(path.string() + ": too short for a Mantaflow config file");
  MantaflowCacheConfig config;
  config.resolution = glm::ivec3(raw.resolution[0], raw.resolution[1], raw.resolution[2]);
  config.normalisedCellSize = raw.dx;
  config.boundsMin = glm::vec3(raw.p0[0], raw.p0[1], raw.p0[2]);
  config.boundsMax = glm::vec3(raw.p1[0], raw.p1[1], raw.p1[2]);
  std::memcpy(&config.worldFromObject[0][0], raw.objectMatrix, sizeof raw.objectMatrix);
  const float cell = config.cellSize();
  if (glm::any(glm::lessThan(config.resolution, glm::ivec3(1))) || !(cell > 0.0f) || !std::isfinite(cell))
    throw Error(path.string() + ": not a Mantaflow config file (resolution or cell size out of range)");
  return config;
}

std::filesystem::path findMantaflowCacheConfig(const std::filesystem::path& particlePattern) {
  const std::filesystem::path directory = particlePattern.parent_path().parent_path() / "config";
  std::error_code error;
  std::vector<std::filesystem::path> found;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("config_", 0) == 0 && entry.path().extension() == ".uni") found.push_back(entry.path());
  }
  if (found.empty()) return {};
  return *std::min_element(found.begin(), found.end());
}

float mantaflowFlatOffset(float kernelRadiusCells, float spacingCells) {
  return flatOffset(kernelRadiusCells, spacingCells, true);
}

LiquidSurfaceFromDomain liquidSurfaceFromDomain(const MantaflowDomainSettings& settings, float cellSize) {
  LiquidSurfaceFromDomain surface;
  // calculateRadiusFactor: half a cell diagonal per unit of mesh_particle_radius, plus Mantaflow's 1 %; in
  // cells of the mesh grid, which is mesh_scale times finer than the simulation's.
  const float meshCell = cellSize / float(settings.meshScale);
  const float kernelCells = 0.5f * std::sqrt(3.0f) * (settings.meshParticleRadius + 0.01f);
  const float spacingCells = float(settings.meshScale) / float(settings.particleNumber);
  surface.meshKernelRadius = kernelCells * meshCell;
  surface.flatOffset = flatOffset(kernelCells, spacingCells, settings.improvedMesh) * meshCell;
  surface.radius = kRadiusPerSpacing * cellSize / float(settings.particleNumber);
  surface.surfaceOffset = std::max(0.0f, surface.flatOffset - kSpindriftFlatOffsetRadii * surface.radius);
  surface.origin = "derived from the Mantaflow domain (cell " + formatNumber(cellSize) +
                   ", particle_number " + std::to_string(settings.particleNumber) +
                   ", mesh_particle_radius " + formatNumber(settings.meshParticleRadius) + ", mesh_scale " +
                   std::to_string(settings.meshScale) + ", " +
                   (settings.improvedMesh ? "IMPROVED" : "UNION") + "): Mantaflow's flat surface stands " +
                   formatNumber(surface.flatOffset) + " off its particles";
  return surface;
}

}  // namespace spindrift
