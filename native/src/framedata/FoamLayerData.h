#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// Foam pass 7: the foam layer the composite puts over the liquid and background, and its parts.
struct FoamLayerData {
  const Texture2D& foam;        ///< RGBA32F premultiplied: iota (I_final - zeta_final), alpha iota.
  const Texture2D& spray;       ///< RGBA32F: the part of `foam` from spray (by share of thickness).
  const Texture2D& surface;     ///< RGBA32F: from surface foam.
  const Texture2D& bubble;      ///< RGBA32F: from bubbles.
  const Texture2D& shadow;      ///< RGBA16F: zeta_final in rgb.
  const Texture2D& irradiance;  ///< RGBA16F: I_final in rgb.
  const Texture2D& thickness;   ///< The thickness pass's per-type thickness, for the output's foam_thickness.
};

}  // namespace spindrift
