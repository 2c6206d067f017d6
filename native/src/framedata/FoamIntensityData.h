#pragma once

#include "gl/GlObjects.h"
#include "gl/LayerCoverage.h"

namespace spindrift {

/// Foam pass 5: the foam's intensity, its opacity in the composite.
struct FoamIntensityData {
  const Texture2D& intensity;  ///< R32F: iota in [0, 1).
  LayerCoverage foamPixels;    ///< where iota > 0: the pixels the foam's later full-screen passes shade
};

}  // namespace spindrift
