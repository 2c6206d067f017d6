#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/DepthLayers.h"
#include "framedata/LightData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// Caustics from the light's view (Wyman and Davis 2006, in screen space): the paths of the light through a
/// grid of the light's view of the liquid (shaders/caustic_paths.comp), then the grid's triangles splatted
/// onto the background where the paths land, each carrying the light of its source area
/// (shaders/caustic_splat.{vert,geom,frag}). The light's view must be bound at binding 2.
class CausticPass {
 public:
  explicit CausticPass(const ShaderLibrary& shaders);
  void begin(int width, int height);
  void addLight(const Light& light, const SurfaceLayers& layers, const BackgroundData& background,
                const LiquidParameters& liquid, const LightParameters& parameters);
  CausticData result() const { return {causticSum_, causticTiles_}; }

 private:
  ProgramObject pathsProgram_;
  ProgramObject splatProgram_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D receiverPosition_;
  Texture2D receiverLight_;
  Texture2D receiverLightTexel_;
  Texture2D causticSum_;
  Texture2D causticTiles_;
};

}  // namespace spindrift
