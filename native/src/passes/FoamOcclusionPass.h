#pragma once

#include <cstdint>

#include "framedata/BackgroundData.h"
#include "framedata/FoamIntensityData.h"
#include "framedata/FoamOcclusionData.h"
#include "framedata/FoamSceneDepth.h"
#include "framedata/FoamSurfaceData.h"
#include "framedata/PixelTiles.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Multi-pass screen-space ambient occlusion with Halton samples, turned into the shadow zeta, and the
/// irradiance from the environment by cosine-weighted sample directions or an irradiance map (foam
/// paper 2.4). With foam.occlusion_block > 1 they are estimated once per block of pixels and upsampled.
class FoamOcclusionPass {
 public:
  /// The largest sample count a pass may take (foam.ao_max_samples' maximum).
  static constexpr int kMaximumSamples = 4096;

  explicit FoamOcclusionPass(const ShaderLibrary& shaders);
  /// With `tiles` (marking every tile with a foam pixel) the full-resolution shadow and irradiance are
  /// shaded in those tiles only, the rest cleared to their no-foam values.
  FoamOcclusionData run(const FoamSurfaceData& surface, const FoamIntensityData& intensity,
                        const FoamSceneDepth& scene, const BackgroundData& background,
                        const FoamParameters& parameters, const PixelTiles* tiles, int width, int height);
  /// The counters of the last run (waits for the GPU).
  FoamOcclusionStatistics statistics() const;

 private:
  void bindEnvironment(GLuint program, const BackgroundData& background) const;

  ProgramObject program_;
  ProgramObject irradianceMapProgram_;
  ProgramObject upsampleProgram_;
  ProgramObject occludersProgram_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  BufferObject haltonSamples_;
  BufferObject counters_;
  Texture2D irradianceMap_;
  Texture2D occluders_;  // what the samples read, one texel per pixel (foam_occluders.frag)
  Texture2D blockShadow_;
  Texture2D blockIrradiance_;
  Texture2D shadow_;
  Texture2D irradiance_;
};

}  // namespace spindrift
