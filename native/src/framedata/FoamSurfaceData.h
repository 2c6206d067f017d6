#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// Foam pass 3: the nearest foam sphere per pixel, and the uploaded particles the thickness pass draws again.
struct FoamSurfaceData {
  const Texture2D& depthAndSearchRadius;  ///< RG32F: planar eye depth (1e10 where none), search radius h.
  const Texture2D& normal;                ///< RGBA16F: world normal, coverage.
  const BufferObject& particles;          ///< FoamInstance[count], shader storage.
  GLsizei count;
};

}  // namespace spindrift
