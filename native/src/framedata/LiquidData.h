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
  /// RGBA32F: where the final refracted ray looks up the background (u, v in 0..1 from the bottom left,
  /// between texel centres), and 1 in B where it does (0 where the light came from elsewhere); 1 in A where
  /// that texel only stands in for a path's end hidden behind a solid (not read back).
  const Texture2D& refractionUv;
  const Texture2D& transmittance;  ///< RGBA32F: the fraction of that background colour that reaches the eye.
  const Texture2D& reflection;  ///< RGBA32F: all other light: liquid = background(uv) * transmittance + this.
};

/// What the rays met, counted on the GPU.
struct RefractionStatistics {
  std::uint32_t liquidPixels = 0;
  std::uint32_t raysWithSecondBody = 0;  ///< Rays that needed a third refraction.
  std::uint32_t totalInternalReflections = 0;
  std::uint32_t exitsOffScreen = 0;  ///< Marches inside a body that left the screen before its far surface.
  std::uint32_t exitsBehindSolids = 0;  ///< Marches inside a body that passed behind a solid hiding it.
  /// Second bodies by order: splash>splash, splash>aggregate, aggregate>splash, aggregate>aggregate.
  std::uint32_t orders[4] = {0, 0, 0, 0};
};

}  // namespace spindrift
