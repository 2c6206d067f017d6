#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// The depth a mesh prepass leaves (OccluderDepthPass): the nearer of the triangles and the depth it started
/// from.
struct OccluderDepthData {
  const Texture2D& eyeDepth;  ///< R32F planar eye depth; 1e10 where nothing is.
};

}  // namespace spindrift
