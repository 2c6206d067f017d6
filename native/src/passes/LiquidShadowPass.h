#pragma once

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/BackgroundPass.h"
#include "passes/EllipsoidImpostorPass.h"
#include "spindrift/Parameters.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// The sums over the lights that the lit background is resolved from.
struct LiquidShadowData {
  const Texture2D& shadowSum;  ///< RGBA32F: (sum of weight x shadow, sum of weight), weight = irradiance.
  const Texture2D& skyKept;    ///< RGBA32F: the sky light a submerged point keeps.
};

/// The liquid's shadow from each light on the background points (shaders/liquid_shadow.frag), and the sky
/// light that points below the liquid's surface keep. `begin` clears the sums; the light's view must be
/// bound at binding 2 (LightDepthLayersPass) when `addLight` or `setSky` runs.
class LiquidShadowPass {
 public:
  explicit LiquidShadowPass(const ShaderLibrary& shaders);
  void begin(int width, int height);
  /// `transmitStraight`: no caustic pass carries the light through the liquid, so the shadow does.
  void addLight(const Light& light, const SurfaceLayers& layers, const BackgroundData& background,
                const LiquidParameters& parameters, bool transmitStraight);
  void setSky(const SurfaceLayers& layers, const BackgroundData& background,
              const LiquidParameters& parameters);
  LiquidShadowData result() const { return {shadowSum_, skyKept_}; }

 private:
  void draw(const Texture2D& target, const SurfaceLayers& layers, const BackgroundData& background,
            const LiquidParameters& parameters, bool sky, bool transmitStraight);

  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D shadowSum_;
  Texture2D skyKept_;
};

}  // namespace spindrift
