#pragma once

#include "framedata/BackgroundData.h"
#include "gl/GlObjects.h"

namespace spindrift {

/// The sums over the lights that the lit background is resolved from (the liquid shadow pass's output).
struct LiquidShadowData {
  const Texture2D& shadowSum;  ///< RGBA32F: (sum of weight x shadow, sum of weight), weight = irradiance.
  /// RGBA32F: the diffuse direct light the lamps give each point without the liquid (irradiance x cos / pi x
  /// colour, the units of Cycles' DiffDir), summed over the lights.
  const Texture2D& lampDiffuse;
};

/// Points per axis of the sky occlusion's samples: it varies over the liquid's size, not the pixel's.
constexpr int kSkyOcclusionScale = 4;

/// The sky and bounced light each background point keeps past liquid other than the body it lies in, one
/// sample per scale × scale pixels (the sky occlusion pass's output).
struct SkyOcclusionData {
  const Texture2D& kept;  ///< RGBA32F: kept light per channel, the sample's eye depth in alpha.
  int scale;              ///< Pixels per sample along each axis.
};

/// The sum over the lights of the light the liquid refracts onto the background (the caustic pass's output).
struct CausticData {
  const Texture2D& causticSum;  ///< RGBA32F: sum of weight x caustic (weights as LiquidShadowData's).
};

/// The background as the liquid lights it, and the passes that say how (the lit background pass's output).
struct LitBackgroundData {
  BackgroundData background;      ///< The original with `color` replaced by the lit colour.
  const Texture2D& liquidShadow;  ///< RGBA32F: what each point keeps of the lights' direct light (rgb).
  const Texture2D& caustics;      ///< RGBA32F: the direct light the liquid refracts onto each point (rgb).
  const Texture2D& skyKept;       ///< RGBA32F: what a point keeps of the sky and bounced light.
};

}  // namespace spindrift
