#pragma once

#include "framedata/DepthLayers.h"

namespace spindrift {

/// The marched first surface at full resolution, split by class into the front layers the refraction pass
/// reads (RaymarchUpsamplePass's output).
struct MarchedFronts {
  DepthLayer splashFront;
  DepthLayer aggregateFront;
};

}  // namespace spindrift
