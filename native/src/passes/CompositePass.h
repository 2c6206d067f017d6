#pragma once

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/BackgroundPass.h"
#include "passes/FoamBlurPass.h"
#include "passes/RefractionPass.h"

namespace spindrift {

/// The final image.
struct CompositeData {
  const Texture2D& color;  ///< RGBA32F, premultiplied.
};

/// Puts the liquid layer over the background and the foam over both.
class CompositePass {
 public:
  explicit CompositePass(const ShaderLibrary& shaders);
  /// `liquid` is null when the frame has no liquid in view, `foam` when it has no foam in view.
  CompositeData run(const BackgroundData& background, const LiquidData* liquid, const FoamLayerData* foam, int width,
                    int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D color_;
};

}  // namespace spindrift
