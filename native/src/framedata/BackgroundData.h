#pragma once

#include <glm/vec3.hpp>

#include "gl/GlObjects.h"

namespace spindrift {

/// What lies behind the liquid, on the GPU, at the camera's size (the background pass's output).
struct BackgroundData {
  const Texture2D& color;        ///< RGBA32F, opaque.
  const Texture2D& eyeDepth;     ///< R32F planar eye depth; 1e10 where nothing is.
  const Texture2D* environment;  ///< Null when the scene has none.
  glm::vec3 fallbackColor;
  /// R32F planar eye depth of a render that includes the liquid, as the file has it; null when none.
  const Texture2D* liquidEyeDepth;
};

}  // namespace spindrift
