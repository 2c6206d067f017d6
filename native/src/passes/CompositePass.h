#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/CompositeData.h"
#include "framedata/FoamLayerData.h"
#include "framedata/LiquidData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"

namespace spindrift {

/// Puts the liquid layer over the background and the foam over both.
class CompositePass {
 public:
  explicit CompositePass(const ShaderLibrary& shaders);
  /// `liquid` is null when the frame has no liquid in view, `foam` when it has no foam in view.
  CompositeData run(const BackgroundData& background, const LiquidData* liquid, const FoamLayerData* foam,
                    int width, int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D color_;
};

}  // namespace spindrift
