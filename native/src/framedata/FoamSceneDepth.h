#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// Foam passes 1 and 2: the eye depths of what can hide or cover foam.
struct FoamSceneDepth {
  const Texture2D& solidEyeDepth;  ///< R32F: the background's solids (BackgroundData::eyeDepth).
  const Texture2D& fluidEyeDepth;  ///< R32F: the liquid's first surface; 1e10 where there is none.
};

}  // namespace spindrift
