#pragma once

#include "framedata/FoamSceneDepth.h"
#include "framedata/FoamSurfaceData.h"
#include "framedata/FoamThicknessData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Sums the foam sprites additively, each weighted by its type's falloff, the lifetime fade and the
/// attenuation below the liquid surface; fragments behind solids are discarded (foam paper 2.2).
class FoamThicknessPass {
 public:
  explicit FoamThicknessPass(const ShaderLibrary& shaders);
  FoamThicknessData run(const FoamSurfaceData& surface, const FoamSceneDepth& scene,
                        const FoamParameters& parameters, int width, int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D thickness_;
};

}  // namespace spindrift
