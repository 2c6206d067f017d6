#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// Where the rays enter, and the screen-space normal N_screen of the adaptive ray marching paper, 4.4
/// (RaymarchEntryPass's output).
struct RaymarchEntryData {
  const Texture2D& allDepth;      ///< R32F D_all: the nearest front surface of every particle.
  const Texture2D& screenNormal;  ///< RGBA16F: normals of the bilateral-smoothed D_all, coverage in w.
};

}  // namespace spindrift
