#pragma once

#include <cstdint>
#include <optional>

#include "framedata/BackgroundData.h"
#include "framedata/DepthLayers.h"
#include "framedata/LiquidData.h"
#include "framedata/PixelTiles.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// Up to four refractions through the splash and aggregate layers with Fresnel, total internal reflection and
/// Beer-Lambert absorption (liquid paper 4.4-4.5).
class RefractionPass {
 public:
  explicit RefractionPass(const ShaderLibrary& shaders);
  /// Either layer set may be absent (no splash, or no aggregate, in view). With `cameraInLiquid` every ray
  /// starts inside the aggregated body and first meets its back layer, the surface seen from below. A path
  /// ends on a solid within two `particleRadius` of the body's drawn back (the liquid rests on it), unless
  /// the solid lies outside a Mantaflow `domain`'s box (air separates Mantaflow's mesh from the domain's
  /// walls). With `tiles` (marking every tile where a layer has a surface; never with the camera in the
  /// liquid, where every pixel is liquid) only those tiles are shaded and the rest hold the no-liquid values.
  LiquidData run(const std::optional<SurfaceLayers>& splashes, const std::optional<SurfaceLayers>& aggregates,
                 const BackgroundData& background, const LiquidParameters& parameters, bool cameraInLiquid,
                 float particleRadius, const DomainBox* domain, const PixelTiles* tiles, int width,
                 int height);
  /// The counters of the last run (waits for the GPU).
  RefractionStatistics statistics() const;

 private:
  /// refraction_layers.frag: the four layers' depths into layerDepths_ and their normals into layerNormals_
  /// (both allocated, and with `tiles` the former cleared, by run).
  void packLayers(const std::optional<SurfaceLayers>& splashes,
                  const std::optional<SurfaceLayers>& aggregates, const PixelTiles* tiles);
  void clearToNoLiquid();

  ProgramObject program_;
  ProgramObject packProgram_;  ///< refraction_layers.frag
  FramebufferObject packFramebuffer_;
  Texture2D layerDepths_;  ///< the four depth layers in one RGBA32F texture
  /// The four layers' normals (RGBA16F) as the layers of one array texture, layer = body × 2 + back, so that
  /// refraction.frag reads one texel where it chose among four textures (and llvmpipe fetched all four).
  Texture2D layerNormals_;
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
