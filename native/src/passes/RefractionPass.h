#pragma once

#include <cstdint>
#include <optional>

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/BackgroundPass.h"
#include "passes/EllipsoidImpostorPass.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// The liquid as the compositor sees it.
struct LiquidData {
  const Texture2D& color;        ///< RGBA32F, premultiplied over transparent.
  const Texture2D& splashColor;  ///< The same where the first surface is a splash, else transparent.
  const Texture2D& surfaceClass; ///< R32F: 0 background, 1 splash, 2 aggregate (the first surface).
  const Texture2D& thickness;    ///< R32F: path length in liquid.
  const Texture2D& frontDepth;   ///< R32F: eye depth of the first surface; 1e10 where none.
  const Texture2D& frontNormal;  ///< RGBA16F: world normal of the first surface, coverage.
  /// RGBA32F: where the final refracted ray looks up the background (u, v in 0..1 from the bottom left, at
  /// the centre of the texel it reads), and 1 in B where it does (0 where the light came from elsewhere).
  const Texture2D& refractionUv;
  const Texture2D& transmittance;  ///< RGBA32F: the fraction of that background colour that reaches the eye.
  const Texture2D& reflection;     ///< RGBA32F: all other light: liquid = background(uv) * transmittance + this.
};

/// What the rays met, counted on the GPU.
struct RefractionStatistics {
  std::uint32_t liquidPixels = 0;
  std::uint32_t raysWithSecondBody = 0;  ///< Rays that needed a third refraction.
  std::uint32_t totalInternalReflections = 0;
  /// Second bodies by order: splash>splash, splash>aggregate, aggregate>splash, aggregate>aggregate.
  std::uint32_t orders[4] = {0, 0, 0, 0};
};

/// Up to four refractions through the splash and aggregate layers with Fresnel, total internal reflection and
/// Beer-Lambert absorption (liquid paper 4.4-4.5).
class RefractionPass {
 public:
  explicit RefractionPass(const ShaderLibrary& shaders);
  /// Either layer set may be absent (no splash, or no aggregate, in view).
  LiquidData run(const std::optional<SurfaceLayers>& splashes, const std::optional<SurfaceLayers>& aggregates,
                 const BackgroundData& background, const LiquidParameters& parameters,
                 int width, int height);
  /// The counters of the last run (waits for the GPU).
  RefractionStatistics statistics() const;

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  BufferObject counters_;
  Texture2D color_;
  Texture2D splashColor_;
  Texture2D surfaceClass_;
  Texture2D thickness_;
  Texture2D frontDepth_;
  Texture2D frontNormal_;
  Texture2D refractionUv_;
  Texture2D transmittance_;
  Texture2D reflection_;
  Texture2D emptyLayer_;  ///< 1x1 "no surface" texture bound in place of an absent layer.
};

}  // namespace spindrift
