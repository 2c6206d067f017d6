#include "passes/RaymarchEntryPass.h"

#include "passes/DepthSmoothingPass.h"

namespace spindrift {

RaymarchEntryPass::RaymarchEntryPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"raymarch_entry.comp"})),
      smoothing_(std::make_unique<DepthSmoothingPass>(shaders)) {}

RaymarchEntryPass::~RaymarchEntryPass() = default;

RaymarchEntryData RaymarchEntryPass::run(const std::optional<SurfaceLayers>& splashes,
                                         const std::optional<SurfaceLayers>& aggregates,
                                         const DepthLayer& emptyLayer, float particleRadius,
                                         const LiquidParameters& parameters, int width, int height) {
  ensureTexture(allDepth_, GL_R32F, width, height);
  ensureTexture(allNormal_, GL_RGBA16F, width, height);
  const DepthLayer& splashFront = splashes ? splashes->front : emptyLayer;
  const DepthLayer& aggregateFront = aggregates ? aggregates->front : emptyLayer;
  glUseProgram(program_.id());
  glBindTextureUnit(0, splashFront.eyeDepth.id());
  glBindTextureUnit(1, splashFront.normal.id());
  glBindTextureUnit(2, aggregateFront.eyeDepth.id());
  glBindTextureUnit(3, aggregateFront.normal.id());
  glBindImageTexture(0, allDepth_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  glBindImageTexture(1, allNormal_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  glDispatchCompute(GLuint((width + 7) / 8), GLuint((height + 7) / 8), 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  checkGlError("finding where the rays enter (D_all)");

  // The liquid pipeline's own smoothing (liquid.smoothing): `bilateral` is the paper's filter; the default
  // plane fit keeps the normals of large on-screen particles free of the separable filter's streaks
  // (docs/raymarch.md, "N_screen from the plane fit").
  const DepthLayer smoothed =
      smoothing_->run({allDepth_, allNormal_}, particleRadius, false, parameters, nullptr, width, height);
  return {allDepth_, smoothed.normal};
}

}  // namespace spindrift
