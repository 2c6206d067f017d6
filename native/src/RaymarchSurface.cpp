#include "RaymarchSurface.h"

#include "Readback.h"

namespace spindrift {

void replaceFrontLayers(const MarchedFronts& fronts, std::optional<SurfaceLayers>& splashes,
                        std::optional<SurfaceLayers>& aggregates) {
  if (splashes) {
    const DepthLayer back = splashes->back;
    splashes.emplace(SurfaceLayers{fronts.splashFront, back});
  }
  if (aggregates) {
    const DepthLayer back = aggregates->back;
    aggregates.emplace(SurfaceLayers{fronts.aggregateFront, back});
  }
}

RaymarchSurface::RaymarchSurface(const ShaderLibrary& shaders)
    : grid_(shaders), mask_(shaders), entry_(shaders), tiles_(shaders), march_(shaders), upsample_(shaders) {}

const DepthLayer& RaymarchSurface::emptyLayer(int width, int height) {
  if (!empty_.eyeDepth.matches(width, height, GL_R32F)) {
    ensureTexture(empty_.eyeDepth, GL_R32F, width, height);
    ensureTexture(empty_.normal, GL_RGBA16F, width, height);
    const float noSurface = 1e10f;
    const float noNormal[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(empty_.eyeDepth.id(), 0, GL_RED, GL_FLOAT, &noSurface);
    glClearTexImage(empty_.normal.id(), 0, GL_RGBA, GL_FLOAT, noNormal);
    emptyLayer_.emplace(DepthLayer{empty_.eyeDepth, empty_.normal});
  }
  return *emptyLayer_;
}

MarchedFronts RaymarchSurface::run(const RaymarchPreparation& preparation,
                                   const std::optional<SurfaceLayers>& splashes,
                                   const std::optional<SurfaceLayers>& aggregates,
                                   const BackgroundData& background, const LiquidParameters& parameters,
                                   PassTimer& timer, int width, int height) {
  const float radius = preparation.particleRadius;
  const DepthLayer& empty = emptyLayer(width, height);
  std::optional<RaymarchGridData> grid;
  std::optional<DensityMaskData> mask;
  std::optional<RaymarchEntryData> entry;
  std::optional<RaymarchTileData> tiles;
  std::optional<RaymarchSamples> samples;
  {
    ScopedPassTimer timed(timer, "raymarch_grid");
    grid.emplace(grid_.run(preparation));
  }
  {
    ScopedPassTimer timed(timer, "raymarch_density_mask");
    mask.emplace(mask_.run(*grid, parameters));
  }
  {
    ScopedPassTimer timed(timer, "raymarch_entry");
    entry.emplace(entry_.run(splashes, aggregates, empty, radius, parameters, width, height));
  }
  {
    ScopedPassTimer timed(timer, "raymarch_tiles");
    tiles.emplace(tiles_.run(*entry, radius, parameters, width, height));
  }
  {
    ScopedPassTimer timed(timer, "raymarch");
    const RaymarchInputs inputs{*entry,
                                *tiles,
                                *grid,
                                *mask,
                                aggregates ? aggregates->front : empty,
                                splashes ? splashes->back : empty,
                                aggregates ? aggregates->back : empty,
                                background,
                                bool(splashes),
                                bool(aggregates),
                                preparation.domain ? &*preparation.domain : nullptr};
    samples.emplace(march_.run(inputs, radius, parameters, width, height));
  }
  ScopedPassTimer timed(timer, "raymarch_upsample");
  lastEntryDepth_ = &entry->allDepth;
  lastSteps_ = &samples->steps;
  lastSampleDepth_ = &samples->depth;
  lastLevels_ = &tiles->levels;
  lastTileSize_ = tiles->tileSize;
  lastStats_ = RaymarchFrameStats{};
  lastStats_.enabled = true;
  lastStats_.densityParticles = preparation.particles.size();
  lastStats_.gridCells = preparation.grid.cellCount();
  lastStats_.adaptiveStepping = parameters.raymarch_stepping == "adaptive";
  return upsample_.run(*samples, *tiles, splashes ? splashes->front : empty,
                       aggregates ? aggregates->front : empty, width, height);
}

RaymarchFrameStats RaymarchSurface::statistics() const {
  RaymarchFrameStats stats = lastStats_;
  if (!stats.enabled) return stats;
  const RaymarchCounters counters = march_.counters();
  const TileHistogram histogram = tiles_.histogram();
  stats.raysCast = counters.rays;
  stats.hits = counters.hits;
  stats.totalSteps = counters.steps;
  stats.averageStepsPerRay = counters.rays ? double(counters.steps) / counters.rays : 0.0;
  stats.densityEvaluationsPerRay = counters.rays ? double(counters.densities) / counters.rays : 0.0;
  stats.refinementEvaluationsPerRay = counters.rays ? double(counters.refinements) / counters.rays : 0.0;
  const double particles = double(counters.particlesHigh) * 4294967296.0 + double(counters.particlesLow);
  stats.particlesVisitedPerRay = counters.rays ? particles / counters.rays : 0.0;
  for (int i = 0; i < 4; ++i)
    stats.tiles[i] = histogram[i];
  return stats;
}

std::vector<ImageLayer> RaymarchSurface::intermediateLayers() const {
  std::vector<ImageLayer> layers;
  if (!lastSteps_) return layers;
  layers.push_back(readLayer(*lastEntryDepth_, "raymarch_entry_depth", {"Z"}));
  layers.push_back(readLayer(*lastSampleDepth_, "raymarch_sample_depth", {"Z"}));
  layers.push_back(readLayer(*lastSteps_, "raymarch_steps", {"Y"}));
  // The tile texture is bottom row first (GL's window coordinates); layers are top row first.
  const Texture2D& levels = *lastLevels_;
  std::vector<std::uint8_t> tileLevels(std::size_t(levels.width) * levels.height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(levels.id(), 0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, GLsizei(tileLevels.size()),
                    tileLevels.data());
  checkGlError("reading the ray-marching tiles");
  const int width = lastSteps_->width, height = lastSteps_->height;
  ImageLayer spacing{"raymarch_ray_spacing", {"Y"}, std::vector<float>(std::size_t(width) * height)};
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column) {
      const int glRow = height - 1 - row;
      const std::uint8_t level =
          tileLevels[std::size_t(glRow / lastTileSize_) * levels.width + std::size_t(column / lastTileSize_)];
      spacing.pixels[std::size_t(row) * width + column] = level < 3 ? float(1 << level) : 0.0f;
    }
  layers.push_back(std::move(spacing));
  return layers;
}

}  // namespace spindrift
