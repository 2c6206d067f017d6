#pragma once

#include "framedata/BackgroundData.h"
#include "framedata/DepthLayers.h"
#include "framedata/LightData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// The liquid's shadow from each light on the background points (shaders/liquid_shadow.frag), and the sky
/// light that points keep: below the liquid's surface, and past other liquid (SkyOcclusionPass's samples).
/// `begin` clears the sums; the light's view must be bound at binding 2 (LightDepthLayers) when `addLight` or
/// `setSky` runs.
class LiquidShadowPass {
 public:
  explicit LiquidShadowPass(const ShaderLibrary& shaders);
  void begin(int width, int height);
  /// `transmitStraight`: no caustic pass carries the light through the liquid, so the shadow does.
  void addLight(const Light& light, const SurfaceLayers& layers, const BackgroundData& background,
                const LiquidParameters& parameters, bool transmitStraight);
  /// `particleRadius`: points up to two radii below the liquid's drawn bottom still lie in it. `occlusion`:
  /// the sky occlusion's samples, or null when it did not run.
  void setSky(const SurfaceLayers& layers, const BackgroundData& background,
              const LiquidParameters& parameters, float particleRadius, const SkyOcclusionData* occlusion);
  LiquidShadowData result() const { return {shadowSum_, skyKept_, lampDiffuse_}; }

 private:
  /// Draws with one of the programs into the framebuffer's bound targets.
  void draw(GLuint program, const SurfaceLayers& layers, const BackgroundData& background);

  // liquid_shadow.frag compiled for each mode: a light whose caustics carry what crosses the liquid, a light
  // whose shadow does, and the sky. Each mode's program holds only its own work (see ShaderLibrary::program).
  ProgramObject lightProgram_;
  ProgramObject straightLightProgram_;
  ProgramObject skyProgram_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D shadowSum_;
  Texture2D skyKept_;
  Texture2D lampDiffuse_;
};

}  // namespace spindrift
