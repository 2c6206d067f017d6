#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "framedata/BackgroundData.h"
#include "framedata/FoamIntensityData.h"
#include "framedata/FoamOcclusionData.h"
#include "framedata/FoamSceneDepth.h"
#include "framedata/FoamSurfaceData.h"
#include "framedata/PixelTiles.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Parameters.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// The foam SSAO's samples that the paper uses, those inside the unit sphere, taken from Halton points in
/// [-1, 1]^3 with their length in w: a point is kept unless its length is above 1 or 0 (as the shader skipped
/// them). `insideAmongFirst[n]` is how many of the first n points are kept (n from 0 to all of them), so that
/// a pass taking n samples of the sequence loops over exactly its kept ones, in the same order.
struct SamplesInsideSphere {
  std::vector<glm::vec4> inside;
  std::vector<std::uint32_t> insideAmongFirst;
};
SamplesInsideSphere samplesInsideUnitSphere(const std::vector<glm::vec4>& cube);

/// Multi-pass screen-space ambient occlusion with Halton samples, turned into the shadow zeta, and the
/// irradiance from the environment by cosine-weighted sample directions or an irradiance map (foam
/// paper 2.4). With foam.occlusion_block > 1 they are estimated once per block of pixels and upsampled.
class FoamOcclusionPass {
 public:
  /// The largest sample count a pass may take (foam.ao_max_samples' maximum).
  static constexpr int kMaximumSamples = 4096;

  explicit FoamOcclusionPass(const ShaderLibrary& shaders);
  /// With `tiles` (marking every tile with a foam pixel) the full-resolution shadow and irradiance are
  /// shaded in those tiles only, the rest cleared to their no-foam values. `lights` add their direct
  /// irradiance to the environment's where foam.lit_by_lights is on.
  FoamOcclusionData run(const FoamSurfaceData& surface, const FoamIntensityData& intensity,
                        const FoamSceneDepth& scene, const BackgroundData& background,
                        const std::vector<Light>& lights, const FoamParameters& parameters,
                        const PixelTiles* tiles, int width, int height);
  /// The counters of the last run (waits for the GPU).
  FoamOcclusionStatistics statistics() const;

 private:
  void bindEnvironment(GLuint program, const BackgroundData& background) const;
  void bindLamps(GLuint program, const std::vector<Light>& lights);

  ProgramObject program_;
  ProgramObject irradianceMapProgram_;
  ProgramObject upsampleProgram_;
  ProgramObject occludersProgram_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  BufferObject haltonSamples_;       // the samples inside the unit sphere, in the sequence's order
  BufferObject haltonInsideCounts_;  // [n]: how many of the sequence's first n samples are inside
  BufferObject counters_;
  BufferObject lamps_;  // the lights that light the foam (shaders/lib/foam_lamps.glsl's FoamLamp each)
  std::size_t lampCapacity_ = 0;
  Texture2D irradianceMap_;
  Texture2D occluders_;  // what the samples read, one texel per pixel (foam_occluders.frag)
  Texture2D blockShadow_;
  Texture2D blockIrradiance_;
  Texture2D shadow_;
  Texture2D irradiance_;
};

}  // namespace spindrift
