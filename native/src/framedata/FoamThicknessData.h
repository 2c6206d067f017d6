#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// Foam pass 4: the foam's thickness per pixel.
struct FoamThicknessData {
  const Texture2D& thickness;  ///< RGBA32F: summed weights of spray (r), surface foam (g) and bubbles (b).
};

}  // namespace spindrift
