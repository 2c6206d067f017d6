#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/LiquidData.h"
#include "framedata/PixelTiles.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"

namespace spindrift {

/// The background each liquid pixel sees, averaged over the pixel's footprint where the refraction shrinks it
/// (liquid.pixel_filter_width; shaders/refraction_footprint.frag says how and docs/liquid.md, "The
/// background's footprint", what it buys). It recombines the refraction's split (reflection + transmittance *
/// background) into the refraction's liquid and splash colours, in place, where a footprint adds to the one
/// lookup the refraction made; elsewhere they keep the refraction's colour. The frame's uniform block
/// (binding 0) must be current.
class RefractionFootprintPass {
 public:
  explicit RefractionFootprintPass(const ShaderLibrary& shaders);
  /// `pixelFilterWidth` is the render's Blackman-Harris pixel filter's width in pixels, as Blender gives it.
  /// With `tiles` (marking every tile the refraction shaded) only those tiles are drawn.
  void run(const LiquidData& liquid, const BackgroundData& background, float pixelFilterWidth,
           const PixelTiles* tiles);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
};

}  // namespace spindrift
