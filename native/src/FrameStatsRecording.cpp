#include "FrameStatsRecording.h"

namespace spindrift {

void recordPreparation(const LiquidPreparation& liquid, const FoamPreparation& foam, FrameStats& stats) {
  stats.liquid.splashParticles = liquid.splashes.size();
  // Shaped as aggregates, whether drawn or left out as hidden (the drops are recorded before this).
  stats.liquid.aggregateParticles =
      liquid.aggregates.size() + stats.liquid.hiddenInteriorDropped + stats.liquid.occludedDropped;
  stats.liquid.isotropicInterior = liquid.isotropicInterior;
  stats.liquid.fullNeighbours = liquid.fullNeighbours;
  stats.liquid.minNeighboursApplied = liquid.minNeighboursApplied;
  stats.liquid.restDensity = liquid.restDensity;
  stats.liquid.culled = liquid.culled;
  stats.liquid.hiddenBehindSolids = liquid.behindSolids;
  stats.liquid.splashesAbsorbed = liquid.splashesAbsorbed;
  stats.liquid.neighbourMilliseconds = liquid.neighbourMilliseconds;
  stats.liquid.anisotropyMilliseconds = liquid.anisotropyMilliseconds;
  stats.foam.sprayParticles = foam.spray;
  stats.foam.surfaceParticles = foam.surface;
  stats.foam.bubbleParticles = foam.bubble;
  stats.foam.culled = foam.culled;
  stats.foam.subPixel = foam.subPixel;
}

void recordLighting(std::size_t sceneLights, const LightingPreparation& lighting, bool lightPasses,
                    LightFrameStats& stats) {
  stats.lights = sceneLights;
  stats.lightsSeeingLiquid = lighting.lights.size();
  stats.lightPasses = lightPasses;
  stats.prepareMilliseconds = lighting.milliseconds;
  stats.viewSize = lighting.viewSize;
  const auto count = [&](const LightPreparation& view) {
    stats.viewParticles += view.liquid.aggregates.size() + view.leftOut;
    stats.viewParticlesLeftOut += view.leftOut;
    stats.viewParticlesColumnThinned += view.columnThinned;
  };
  for (const LightPreparation& light : lighting.lights)
    count(light);
  if (lighting.sky) count(*lighting.sky);
}

void recordRefraction(const RefractionStatistics& rays, LiquidFrameStats& stats) {
  stats.liquidPixels = rays.liquidPixels;
  stats.raysWithSecondBody = rays.raysWithSecondBody;
  stats.totalInternalReflections = rays.totalInternalReflections;
  stats.exitsOffScreen = rays.exitsOffScreen;
  stats.exitsBehindSolids = rays.exitsBehindSolids;
  for (int i = 0; i < 4; ++i)
    stats.orders[i] = rays.orders[i];
}

void recordFoamOcclusion(const FoamOcclusionStatistics& occlusion, FoamFrameStats& stats) {
  stats.foamPixels = occlusion.foamPixels;
  stats.occlusionEstimates = occlusion.estimates;
  stats.aoSamplesPerPixel = occlusion.foamPixels ? double(occlusion.samples) / occlusion.foamPixels : 0.0;
}

void recordFoamCulling(const VisibleFoam& visible, FoamFrameStats& stats) {
  stats.hiddenBehindSolids = visible.behindSolids;
  stats.hiddenUnderLiquid = visible.underLiquid;
}

void recordSurfaceRelaxation(const SurfaceRelaxationStats& relaxation, LiquidFrameStats& stats) {
  stats.surfaceParticles = relaxation.surfaceParticles;
  stats.surfaceRaised = relaxation.raised;
  stats.surfaceSpacing = relaxation.spacing;
  stats.surfaceRelaxationMilliseconds = relaxation.milliseconds;
  stats.surfaceRelaxationNotApplied = relaxation.notApplied;
  stats.surfaceRelaxationKept = relaxation.kept;
}

}  // namespace spindrift
