#pragma once

#include "framedata/FoamOcclusionData.h"
#include "framedata/LiquidData.h"
#include "prep/FoamPreparation.h"
#include "prep/HiddenFoam.h"
#include "prep/LightViews.h"
#include "prep/LiquidPreparation.h"
#include "prep/SurfaceRelaxation.h"
#include "spindrift/RenderResult.h"

namespace spindrift {

/// Copies what the CPU preparation found (particles by role, culled, its timings) into the frame's stats.
void recordPreparation(const LiquidPreparation& liquid, const FoamPreparation& foam, FrameStats& stats);
/// Records the scene's lights, how many see the liquid, what preparing their views cost, and whether the
/// background came with Cycles' light passes.
void recordLighting(std::size_t sceneLights, const LightingPreparation& lighting, bool lightPasses,
                    LightFrameStats& stats);
/// Copies what the surface relaxation did (liquid.relax_surface) into the liquid stats.
void recordSurfaceRelaxation(const SurfaceRelaxationStats& relaxation, LiquidFrameStats& stats);
/// Copies the refraction pass's GPU counters into the liquid stats.
void recordRefraction(const RefractionStatistics& rays, LiquidFrameStats& stats);
/// Copies the counts of the foam particles the sprite passes left out into the foam stats.
void recordFoamCulling(const VisibleFoam& visible, FoamFrameStats& stats);
/// Copies the foam occlusion pass's GPU counters into the foam stats.
void recordFoamOcclusion(const FoamOcclusionStatistics& occlusion, FoamFrameStats& stats);

}  // namespace spindrift
