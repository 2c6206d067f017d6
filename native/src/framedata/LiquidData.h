#pragma once

#include <cstdint>

#include "gl/GlObjects.h"

namespace spindrift {

/// The liquid as the compositor sees it (the refraction pass's output).
struct LiquidData {
  const Texture2D& color;         ///< RGBA32F, premultiplied over transparent.
  const Texture2D& splashColor;   ///< The same where the first surface is a splash, else transparent.
  const Texture2D& surfaceClass;  ///< R32F: 0 background, 1 splash, 2 aggregate (the first surface).
  const Texture2D& thickness;     ///< R32F: path length in liquid.
  const Texture2D& frontDepth;    ///< R32F: eye depth of the first surface; 1e10 where none.
  const Texture2D& frontNormal;   ///< RGBA16F: world normal of the first surface, coverage.
};

/// What the rays met, counted on the GPU.
struct RefractionStatistics {
  std::uint32_t liquidPixels = 0;
  std::uint32_t raysWithSecondBody = 0;  ///< Rays that needed a third refraction.
  std::uint32_t totalInternalReflections = 0;
  /// Second bodies by order: splash>splash, splash>aggregate, aggregate>splash, aggregate>aggregate.
  std::uint32_t orders[4] = {0, 0, 0, 0};
};

}  // namespace spindrift
