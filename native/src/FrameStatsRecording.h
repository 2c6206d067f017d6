#pragma once

#include "framedata/FoamOcclusionData.h"
#include "framedata/LiquidData.h"
#include "prep/FoamPreparation.h"
#include "prep/LiquidPreparation.h"
#include "spindrift/RenderResult.h"

namespace spindrift {

/// Copies what the CPU preparation found (particles by role, culled, its timings) into the frame's stats.
void recordPreparation(const LiquidPreparation& liquid, const FoamPreparation& foam, FrameStats& stats);
/// Copies the refraction pass's GPU counters into the liquid stats.
void recordRefraction(const RefractionStatistics& rays, LiquidFrameStats& stats);
/// Copies the foam occlusion pass's GPU counters into the foam stats.
void recordFoamOcclusion(const FoamOcclusionStatistics& occlusion, FoamFrameStats& stats);

}  // namespace spindrift
