#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/DepthLayers.h"
#include "framedata/LightData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// The liquid's shadow from each light on the background points (shaders/liquid_shadow.frag). `begin` clears
/// the sums; the light's view must be bound at binding 2 (LightDepthLayers) when `addLight` runs.
class LiquidShadowPass {
 public:
  explicit LiquidShadowPass(const ShaderLibrary& shaders);
  void begin(int width, int height);
  /// `transmitStraight`: no caustic pass carries the light through the liquid, so the shadow does.
  void addLight(const Light& light, const SurfaceLayers& layers, const BackgroundData& background,
                const LiquidParameters& parameters, bool transmitStraight);
  LiquidShadowData result() const { return {shadowSum_, lampDiffuse_}; }

 private:
  // liquid_shadow.frag compiled for each mode: a light whose caustics carry what crosses the liquid, and a
  // light whose shadow does. Each mode's program holds only its own work (see ShaderLibrary::program).
  ProgramObject lightProgram_;
  ProgramObject straightLightProgram_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D shadowSum_;
  Texture2D lampDiffuse_;
};

}  // namespace spindrift
