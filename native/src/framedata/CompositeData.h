#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// The final image.
struct CompositeData {
  const Texture2D& color;  ///< RGBA32F, premultiplied.
};

}  // namespace spindrift
