#pragma once

#include "spindrift/Limits.h"

namespace spindrift {

/// Reads GL_MAX_TEXTURE_SIZE, GL_MAX_VIEWPORT_DIMS and GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT; call on the GL
/// thread.
GlLimits queryGlLimits();

}  // namespace spindrift
