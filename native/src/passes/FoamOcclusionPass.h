#pragma once

#include <cstdint>

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/BackgroundPass.h"
#include "passes/FoamDepthPass.h"
#include "passes/FoamIntensityPass.h"
#include "passes/FoamSceneDepthPass.h"
#include "spindrift/Parameters.h"

namespace spindrift {

/// Foam pass 6: how much light each foam pixel receives.
struct FoamOcclusionData {
  const Texture2D& shadow;      ///< R32F: zeta in [0, 1].
  const Texture2D& irradiance;  ///< RGBA16F: I in rgb.
};

/// What the occlusion pass did, counted on the GPU.
struct FoamOcclusionStatistics {
  std::uint32_t foamPixels = 0;
  std::uint64_t samples = 0;  ///< SSAO samples generated (nu summed over passes and pixels).
};

/// Multi-pass screen-space ambient occlusion with Halton samples, turned into the shadow zeta, and the
/// irradiance from the environment by cosine-weighted sample directions or an irradiance map (foam
/// paper 2.4).
class FoamOcclusionPass {
 public:
  /// The largest sample count a pass may take (foam.ao_max_samples' maximum).
  static constexpr int kMaximumSamples = 4096;

  explicit FoamOcclusionPass(const ShaderLibrary& shaders);
  FoamOcclusionData run(const FoamSurfaceData& surface, const FoamIntensityData& intensity,
                        const FoamSceneDepth& scene, const BackgroundData& background,
                        const FoamParameters& parameters, int width, int height);
  /// The counters of the last run (waits for the GPU).
  FoamOcclusionStatistics statistics() const;

 private:
  void bindEnvironment(GLuint program, const BackgroundData& background) const;

  ProgramObject program_;
  ProgramObject irradianceMapProgram_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  BufferObject haltonSamples_;
  BufferObject counters_;
  Texture2D irradianceMap_;
  Texture2D shadow_;
  Texture2D irradiance_;
};

}  // namespace spindrift
