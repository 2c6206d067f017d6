#pragma once

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/BackgroundPass.h"
#include "passes/SphereImpostorPass.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// The liquid layer: premultiplied RGBA over transparent.
struct LiquidData {
  const Texture2D& color;  ///< RGBA32F.
};

/// Shades the nearest liquid surface with the foundation's lit material (liquid.* parameters).
class LiquidShadePass {
 public:
  explicit LiquidShadePass(const ShaderLibrary& shaders);
  LiquidData run(const SurfaceData& surface, const BackgroundData& background, const LiquidParameters& parameters,
                 int width, int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D color_;
};

}  // namespace spindrift
