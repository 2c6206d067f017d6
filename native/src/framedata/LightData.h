#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/DepthLayers.h"
#include "framedata/PixelTiles.h"
#include "gl/GlObjects.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// The sums over the lights that the lit background is resolved from (the liquid shadow pass's output).
struct LiquidShadowData {
  const Texture2D& shadowSum;  ///< RGBA32F: (sum of weight x shadow, sum of weight), weight = irradiance.
  /// RGBA32F: the diffuse direct light the lamps give each point without the liquid (irradiance x cos / pi x
  /// colour, the units of Cycles' DiffDir), summed over the lights.
  const Texture2D& lampDiffuse;
};

/// The sky and bounced light each background point keeps past liquid other than the body it lies in, one
/// sample per scale × scale pixels (the sky occlusion pass's output).
struct SkyOcclusionData {
  const Texture2D& kept;  ///< RGBA32F: kept light per channel, the sample's eye depth in alpha.
  int scale;              ///< Pixels per sample along each axis.
};

/// The sum over the lights of the light the liquid refracts onto the background (the caustic pass's output).
struct CausticData {
  const Texture2D& causticSum;  ///< RGBA32F: sum of weight x caustic (weights as LiquidShadowData's).
  const Texture2D& tiles;       ///< R8UI, a texel per pixel tile: 1 where a splat landed in the tile.
};

/// The sky's view of the liquid, which the lit background finds the sky light each point keeps from.
struct SkyView {
  const SurfaceLayers& layers;        ///< The liquid seen from straight above (LightDepthLayers).
  const SkyOcclusionData* occlusion;  ///< The sky occlusion's samples, or null when it did not run.
  float particleRadius;               ///< Points two radii below the drawn bottom still lie in it.
};

/// Where the lit background gets the lamps' direct light from: the shadow pass's sums over the lights, or the
/// one light whose shadow it finds itself (its caustics on, and the sky occlusion's samples there), whose
/// view must then be bound at binding 2 (LightDepthLayers) when `run` runs.
struct LampLight {
  const LiquidShadowData* sums = nullptr;
  const Light* light = nullptr;
  const SurfaceLayers* layers = nullptr;  ///< The one light's.
  /// No lamp sees the liquid: the world's light alone lights the background, all of it sky light.
  bool none = false;
};

/// The pixel tiles where the lights change the background and those where they do not (the lit tile pass's
/// output): the lit background shades the first and writes the background as it is into the others.
struct LitTiles {
  PixelTiles lit;
  PixelTiles plain;
};

/// The background as the liquid lights it, and the passes that say how (the lit background pass's output).
struct LitBackgroundData {
  BackgroundData background;      ///< The original with `color` replaced by the lit colour.
  const Texture2D& liquidShadow;  ///< RGBA32F: what each point keeps of the lights' direct light (rgb).
  const Texture2D& caustics;      ///< RGBA32F: the direct light the liquid refracts onto each point (rgb).
  const Texture2D& skyKept;       ///< RGBA32F: what a point keeps of the sky and bounced light.
};

}  // namespace spindrift
