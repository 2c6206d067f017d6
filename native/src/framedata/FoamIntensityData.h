#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// Foam pass 5: the foam's intensity, its opacity in the composite.
struct FoamIntensityData {
  const Texture2D& intensity;  ///< R32F: iota in [0, 1).
};

}  // namespace spindrift
