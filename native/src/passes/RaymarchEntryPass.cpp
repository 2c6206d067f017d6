#include "passes/RaymarchEntryPass.h"

#include "passes/BilateralFilterPass.h"
#include "passes/DepthPingPong.h"
#include "passes/NormalsFromDepthPass.h"

namespace spindrift {

// Like DepthSmoothingPass, a pass made of passes: D_all is smoothed and its normals recomputed by the liquid
// pipeline's own bilateral filter and normals passes.
struct RaymarchEntryPass::Smoothing {
  explicit Smoothing(const ShaderLibrary& shaders) : bilateral(shaders), normals(shaders) {}
  BilateralFilterPass bilateral;
  NormalsFromDepthPass normals;
  DepthPingPong targets;
};

RaymarchEntryPass::RaymarchEntryPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"raymarch_entry.comp"})), smoothing_(std::make_unique<Smoothing>(shaders)) {}

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

  smoothing_->targets.resize(width, height);
  const Texture2D& smoothed =
      smoothing_->bilateral.run(allDepth_, particleRadius, parameters, smoothing_->targets).eyeDepth;
  const Texture2D& normal = smoothing_->normals.run(smoothed, allNormal_, false, width, height).normal;
  return {allDepth_, normal};
}

}  // namespace spindrift
