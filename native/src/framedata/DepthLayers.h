#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// One depth layer of the liquid: the front or back surface of the splashes or of the aggregated body.
struct DepthLayer {
  const Texture2D& eyeDepth;  ///< R32F planar eye depth; 1e10 (kNoSurfaceDepth) where the layer is empty.
  const Texture2D& normal;    ///< RGBA16F: world-space outward normal in xyz, coverage (1 or 0) in w.
};

/// The front and back surfaces of one group of liquid particles (the splashes, or the aggregated body): what
/// the ellipsoid impostor pass produces and the depth smoothing pass replaces.
struct SurfaceLayers {
  DepthLayer front;  ///< Nearest front-facing surface.
  DepthLayer back;   ///< Farthest back-facing surface.
};

}  // namespace spindrift
