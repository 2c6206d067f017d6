#include "spindrift/Renderer.h"

#include <algorithm>
#include <chrono>
#include <optional>

#include "gl/GlThread.h"
#include "gl/PassTimer.h"
#include "gl/ShaderLibrary.h"
#include "passes/BackgroundPass.h"
#include "passes/CompositePass.h"
#include "passes/DepthSmoothingPass.h"
#include "passes/EllipsoidImpostorPass.h"
#include "passes/FoamBlurPass.h"
#include "passes/FoamDepthPass.h"
#include "passes/FoamIntensityPass.h"
#include "passes/FoamOcclusionPass.h"
#include "passes/FoamSceneDepthPass.h"
#include "passes/FoamThicknessPass.h"
#include "passes/FrameUniforms.h"
#include "passes/RefractionPass.h"
#include "prep/BackgroundCache.h"
#include "prep/FoamPreparation.h"
#include "prep/LiquidPreparation.h"
#include "Readback.h"

namespace spindrift {
namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Every GL object of the frame; made, used and destroyed on the GL thread.
struct FramePipeline {
  ShaderLibrary shaders{findShaderDirectory()};
  FrameUniformBuffer frameUniforms;
  PassTimer timer;
  BackgroundPass background{shaders};
  EllipsoidImpostorPass splashImpostors{shaders};
  EllipsoidImpostorPass aggregateImpostors{shaders};
  DepthSmoothingPass frontSmoothing{shaders};
  DepthSmoothingPass backSmoothing{shaders};
  RefractionPass refraction{shaders};
  FoamSceneDepthPass foamSceneDepth{shaders};
  FoamDepthPass foamDepth{shaders};
  FoamThicknessPass foamThickness{shaders};
  FoamIntensityPass foamIntensity{shaders};
  FoamOcclusionPass foamOcclusion{shaders};
  FoamBlurPass foamBlur{shaders};
  CompositePass composite{shaders};
};

// The radius r that the paper's parameters are scaled by: the median radius of the liquid particles.
float typicalLiquidRadius(const Particles& particles) {
  std::vector<float> radii;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (particles.kinds[i] == ParticleKind::Liquid) radii.push_back(particles.radii[i]);
  if (radii.empty()) return 1.0f;
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  return radii[radii.size() / 2];
}

}  // namespace

struct Renderer::Impl {
  GlThread glThread;
  std::unique_ptr<FramePipeline> pipeline;  // Lives on glThread; reset there before the thread ends.
  BackgroundCache backgroundCache;
  bool intermediateLayers = false;

  ~Impl() {
    glThread.run([this] { pipeline.reset(); });
  }
};

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {
  impl_->glThread.run([this] { impl_->pipeline = std::make_unique<FramePipeline>(); });
}

Renderer::~Renderer() = default;

void Renderer::setIntermediateLayers(bool enabled) { impl_->intermediateLayers = enabled; }

std::string Renderer::glRenderer() const { return impl_->glThread.renderer(); }
std::string Renderer::glVersion() const { return impl_->glThread.version(); }

RenderResult Renderer::renderFrame(const Scene& scene, int frame) {
  const Clock::time_point start = Clock::now();
  ParticleCounts counts;
  const Particles particles = loadParticles(scene, frame, &counts);
  const double loadMilliseconds = millisecondsSince(start);
  RenderResult result = renderParticles(scene, particles, frame);
  result.stats.counts = counts;
  result.stats.loadMilliseconds = loadMilliseconds;
  result.stats.totalMilliseconds = millisecondsSince(start);
  return result;
}

// The frame, top to bottom, as the liquid paper's figure 4 draws it: prepare the particles on the CPU (split
// into splashes and aggregates, anisotropic ellipsoids; foam culled and packed), then on the GL thread the
// background, the front and back depth layers of splashes and of aggregates, smoothing of the aggregate layers,
// refraction, the foam paper's seven passes (figure 2), and the composite; then read the layers back. A pass the frame does not need is not run, and the stats say why.
RenderResult Renderer::renderParticles(const Scene& scene, const Particles& particles, int frame) {
  const Clock::time_point start = Clock::now();
  const Camera& camera = scene.camera;
  const LiquidParameters& liquidParameters = scene.parameters.liquid;
  const FoamParameters& foamParameters = scene.parameters.foam;
  const int width = camera.width, height = camera.height;
  // A Mantaflow liquid is clipped to its domain's box, as Mantaflow closes its mesh at the walls.
  const DomainBox* domainBox = nullptr;
  for (const ParticleSource& source : scene.particles)
    if (source.role == ParticleRole::Liquid && source.domainBox && !domainBox) domainBox = &*source.domainBox;
  RenderResult result;
  result.width = width;
  result.height = height;
  FrameStats& stats = result.stats;
  stats.frame = frame;
  stats.width = width;
  stats.height = height;
  stats.glRenderer = glRenderer();
  stats.glVersion = glVersion();
  stats.counts = countByKind(particles);

  const Clock::time_point prepareStart = Clock::now();
  const LiquidPreparation liquid = prepareLiquid(particles, camera, liquidParameters);
  const float radius = typicalLiquidRadius(particles);
  const FoamPreparation foam = prepareFoam(particles, camera, foamParameters);
  const BackgroundImages backgroundImages = impl_->backgroundCache.load(scene.background, frame, width, height);
  stats.prepareMilliseconds = millisecondsSince(prepareStart);
  stats.liquid.splashParticles = liquid.splashes.size();
  stats.liquid.aggregateParticles = liquid.aggregates.size();
  stats.liquid.isotropicInterior = liquid.isotropicInterior;
  stats.liquid.culled = liquid.culled;
  stats.liquid.neighbourMilliseconds = liquid.neighbourMilliseconds;
  stats.liquid.anisotropyMilliseconds = liquid.anisotropyMilliseconds;
  stats.foam.sprayParticles = foam.spray;
  stats.foam.surfaceParticles = foam.surface;
  stats.foam.bubbleParticles = foam.bubble;
  stats.foam.culled = foam.culled;

  impl_->glThread.run([&] {
    FramePipeline& pipeline = *impl_->pipeline;
    PassTimer& timer = pipeline.timer;
    auto skip = [&](const char* pass, const char* reason) { stats.skipped.push_back({pass, reason}); };
    pipeline.frameUniforms.update(camera);

    std::optional<BackgroundData> background;
    {
      ScopedPassTimer timed(timer, "background");
      background.emplace(pipeline.background.run(backgroundImages, width, height));
    }
    std::vector<ImageLayer> intermediate;
    auto keep = [&](const SurfaceLayers& layers, const std::string& name) {
      if (!impl_->intermediateLayers) return;
      intermediate.push_back(readLayer(layers.front.eyeDepth, name + "_front_depth", {"Z"}));
      intermediate.push_back(readLayer(layers.back.eyeDepth, name + "_back_depth", {"Z"}));
      intermediate.push_back(readLayer(layers.front.normal, name + "_front_normal", {"X", "Y", "Z"}));
      intermediate.push_back(readLayer(layers.back.normal, name + "_back_normal", {"X", "Y", "Z"}));
    };
    std::optional<SurfaceLayers> splashes;
    if (!liquid.splashes.empty()) {
      {
        ScopedPassTimer timed(timer, "splash_depth_layers");
        splashes.emplace(pipeline.splashImpostors.run(liquid.splashes, *background, width, height, domainBox));
      }
      keep(*splashes, "splash");
    } else {
      skip("splash_depth_layers", "no splash particles in view");
    }
    std::optional<SurfaceLayers> aggregates;
    if (!liquid.aggregates.empty()) {
      {
        ScopedPassTimer timed(timer, "aggregate_depth_layers");
        aggregates.emplace(pipeline.aggregateImpostors.run(liquid.aggregates, *background, width, height, domainBox));
      }
      keep(*aggregates, "aggregate");
      if (liquidParameters.smoothing != "none") {
        ScopedPassTimer timed(timer, "smoothing");
        const DepthLayer front = pipeline.frontSmoothing.run(aggregates->front, radius, false, liquidParameters, width, height);
        const DepthLayer back = pipeline.backSmoothing.run(aggregates->back, radius, true, liquidParameters, width, height);
        aggregates.emplace(SurfaceLayers{front, back});
        keep(*aggregates, "aggregate_smoothed");
      } else {
        skip("smoothing", "liquid.smoothing is none");
      }
    } else {
      skip("aggregate_depth_layers", "no aggregate particles in view");
      skip("smoothing", "no aggregate particles in view");
    }
    std::optional<LiquidData> liquidLayer;
    if (splashes || aggregates) {
      ScopedPassTimer timed(timer, "refraction");
      liquidLayer.emplace(pipeline.refraction.run(splashes, aggregates, *background, liquidParameters, width, height));
    } else {
      skip("refraction", "no liquid particles in view");
    }
    // Foam (foam paper, figure 2): the solids' and the liquid's depth, the foam's nearest depth, its thickness,
    // intensity, shadow and irradiance, then blur and the foam layer.
    std::optional<FoamLayerData> foamLayer;
    if (!foam.instances.empty()) {
      std::optional<FoamSceneDepth> sceneDepth;
      std::optional<FoamSurfaceData> foamSurface;
      std::optional<FoamThicknessData> foamThickness;
      std::optional<FoamIntensityData> foamIntensity;
      std::optional<FoamOcclusionData> foamOcclusion;
      {
        ScopedPassTimer timed(timer, "foam_scene_depth");
        sceneDepth.emplace(pipeline.foamSceneDepth.run(*background, liquidLayer ? &liquidLayer->frontDepth : nullptr,
                                                       width, height));
      }
      {
        ScopedPassTimer timed(timer, "foam_depth");
        foamSurface.emplace(pipeline.foamDepth.run(foam.instances, *sceneDepth, width, height));
      }
      {
        ScopedPassTimer timed(timer, "foam_thickness");
        foamThickness.emplace(pipeline.foamThickness.run(*foamSurface, *sceneDepth, foamParameters, width, height));
      }
      {
        ScopedPassTimer timed(timer, "foam_intensity");
        foamIntensity.emplace(pipeline.foamIntensity.run(*foamThickness, foamParameters, width, height));
      }
      {
        ScopedPassTimer timed(timer, "foam_occlusion");
        foamOcclusion.emplace(pipeline.foamOcclusion.run(*foamSurface, *foamIntensity, *sceneDepth, *background,
                                                         foamParameters, width, height));
      }
      {
        ScopedPassTimer timed(timer, "foam_blur");
        foamLayer.emplace(pipeline.foamBlur.run(*foamSurface, *foamThickness, *foamIntensity, *foamOcclusion,
                                                foamParameters, width, height));
      }
    } else {
      for (const char* pass : {"foam_scene_depth", "foam_depth", "foam_thickness", "foam_intensity", "foam_occlusion",
                               "foam_blur"})
        skip(pass, "no foam particles in view");
    }
    std::optional<CompositeData> composite;
    {
      ScopedPassTimer timed(timer, "composite");
      composite.emplace(pipeline.composite.run(*background, liquidLayer ? &*liquidLayer : nullptr,
                                               foamLayer ? &*foamLayer : nullptr, width, height));
    }
    stats.passes = timer.collect();

    const Clock::time_point readbackStart = Clock::now();
    result.layers.push_back(readLayer(composite->color, "composite", {"R", "G", "B", "A"}));
    if (liquidLayer) {
      const RefractionStatistics rays = pipeline.refraction.statistics();
      stats.liquid.liquidPixels = rays.liquidPixels;
      stats.liquid.raysWithSecondBody = rays.raysWithSecondBody;
      stats.liquid.totalInternalReflections = rays.totalInternalReflections;
      for (int i = 0; i < 4; ++i) stats.liquid.orders[i] = rays.orders[i];
      result.layers.push_back(readLayer(liquidLayer->color, "liquid", {"R", "G", "B", "A"}));
      result.layers.push_back(readLayer(liquidLayer->splashColor, "liquid_splash", {"R", "G", "B", "A"}));
      result.layers.push_back(readLayer(liquidLayer->surfaceClass, "liquid_class", {"Y"}));
      result.layers.push_back(readLayer(liquidLayer->frontDepth, "depth", {"Z"}));
      result.layers.push_back(readLayer(liquidLayer->frontNormal, "normal", {"X", "Y", "Z"}));
      result.layers.push_back(readLayer(liquidLayer->thickness, "thickness", {"Y"}));
    } else {
      // The layers stay in the file so every frame of a sequence has the same channels.
      result.layers.push_back(filledLayer(width, height, "liquid", {"R", "G", "B", "A"}, 0.0f));
      result.layers.push_back(filledLayer(width, height, "liquid_splash", {"R", "G", "B", "A"}, 0.0f));
      result.layers.push_back(filledLayer(width, height, "liquid_class", {"Y"}, 0.0f));
      result.layers.push_back(filledLayer(width, height, "depth", {"Z"}, 1e10f));
      result.layers.push_back(filledLayer(width, height, "normal", {"X", "Y", "Z"}, 0.0f));
      result.layers.push_back(filledLayer(width, height, "thickness", {"Y"}, 0.0f));
    }
    if (foamLayer) {
      const FoamOcclusionStatistics occlusion = pipeline.foamOcclusion.statistics();
      stats.foam.foamPixels = occlusion.foamPixels;
      stats.foam.aoSamplesPerPixel = occlusion.foamPixels ? double(occlusion.samples) / occlusion.foamPixels : 0.0;
    }
    readFoamLayers(foamLayer ? &*foamLayer : nullptr, width, height, result.layers);
    for (ImageLayer& layer : intermediate) result.layers.push_back(std::move(layer));
    stats.readbackMilliseconds = millisecondsSince(readbackStart);
  });
  stats.totalMilliseconds = millisecondsSince(start);
  return result;
}

}  // namespace spindrift
