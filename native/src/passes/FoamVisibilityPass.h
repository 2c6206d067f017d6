#pragma once

#include "framedata/FoamSceneDepth.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "prep/HiddenFoam.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Per tile of 8 x 8 pixels, the eye depth beyond which a foam fragment shows in no foam layer: behind the
/// solids, or deeper under the liquid than foam.attenuation_distance (where f_att is 0). Read back (a few
/// kilobytes), so that the CPU leaves hidden particles out before the sprite passes (cullHiddenFoam).
class FoamVisibilityPass {
 public:
  static constexpr int kTileSize = 8;

  explicit FoamVisibilityPass(const ShaderLibrary& shaders);
  FoamVisibilityTiles run(const FoamSceneDepth& scene, const FoamParameters& parameters, int width,
                          int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D hiddenBeyondTiles_;
};

}  // namespace spindrift
