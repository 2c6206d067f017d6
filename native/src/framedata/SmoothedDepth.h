#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// The eye depth a smoothing filter produces: R32F, kNoSurfaceDepth where the layer is empty.
struct SmoothedDepth {
  const Texture2D& eyeDepth;
};

/// Normals recomputed from a smoothed depth layer.
struct RecomputedNormals {
  const Texture2D& normal;  ///< RGBA16F: world-space outward normal in xyz, coverage (1 or 0) in w.
};

}  // namespace spindrift
