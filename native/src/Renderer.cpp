#include "spindrift/Renderer.h"

#include <chrono>

#include "gl/GlThread.h"
#include "gl/PassTimer.h"
#include "gl/ShaderLibrary.h"
#include "passes/BackgroundPass.h"
#include "passes/CompositePass.h"
#include "passes/FrameUniforms.h"
#include "passes/LiquidShadePass.h"
#include "passes/SphereImpostorPass.h"
#include "prep/BackgroundCache.h"
#include "prep/VisibleSpheres.h"
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
  SphereImpostorPass sphereImpostors{shaders};
  LiquidShadePass liquidShade{shaders};
  CompositePass composite{shaders};
};

}  // namespace

struct Renderer::Impl {
  GlThread glThread;
  std::unique_ptr<FramePipeline> pipeline;  // Lives on glThread; reset there before the thread ends.
  BackgroundCache backgroundCache;

  ~Impl() {
    glThread.run([this] { pipeline.reset(); });
  }
};

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {
  impl_->glThread.run([this] { impl_->pipeline = std::make_unique<FramePipeline>(); });
}

Renderer::~Renderer() = default;

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

// The frame, top to bottom: prepare on the CPU, then background → sphere impostors → liquid shading →
// composite on the GL thread, then read the layers back. A pass the frame does not need is not run, and the
// stats say why.
RenderResult Renderer::renderParticles(const Scene& scene, const Particles& particles, int frame) {
  const Clock::time_point start = Clock::now();
  const Camera& camera = scene.camera;
  const int width = camera.width, height = camera.height;
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
  const VisibleSpheres liquid = visibleSpheres(particles, ParticleKind::Liquid, camera);
  const BackgroundImages backgroundImages = impl_->backgroundCache.load(scene.background, frame, width, height);
  stats.liquidParticlesDrawn = liquid.spheres.size();
  stats.prepareMilliseconds = millisecondsSince(prepareStart);

  impl_->glThread.run([&] {
    FramePipeline& pipeline = *impl_->pipeline;
    PassTimer& timer = pipeline.timer;
    pipeline.frameUniforms.update(camera);

    std::optional<BackgroundData> background;
    {
      ScopedPassTimer timed(timer, "background");
      background.emplace(pipeline.background.run(backgroundImages, width, height));
    }
    std::optional<SurfaceData> surface;
    std::optional<LiquidData> liquidLayer;
    if (!liquid.spheres.empty()) {
      {
        ScopedPassTimer timed(timer, "sphere_impostors");
        surface.emplace(pipeline.sphereImpostors.run(liquid.spheres, *background, width, height));
      }
      ScopedPassTimer timed(timer, "liquid_shade");
      liquidLayer.emplace(pipeline.liquidShade.run(*surface, *background, scene.parameters.liquid, width, height));
    } else {
      const std::string reason = "no liquid particles in view";
      stats.skipped.push_back({"sphere_impostors", reason});
      stats.skipped.push_back({"liquid_shade", reason});
    }
    std::optional<CompositeData> composite;
    {
      ScopedPassTimer timed(timer, "composite");
      composite.emplace(pipeline.composite.run(*background, liquidLayer ? &*liquidLayer : nullptr, width, height));
    }
    stats.passes = timer.collect();

    const Clock::time_point readbackStart = Clock::now();
    result.layers.push_back(readLayer(composite->color, "composite", {"R", "G", "B", "A"}));
    if (liquidLayer) {
      result.layers.push_back(readLayer(liquidLayer->color, "liquid", {"R", "G", "B", "A"}));
      result.layers.push_back(readLayer(surface->eyeDepth, "depth", {"Z"}));
      result.layers.push_back(readLayer(surface->normal, "normal", {"X", "Y", "Z"}));
    } else {
      // The layers stay in the file so every frame of a sequence has the same channels.
      result.layers.push_back(filledLayer(width, height, "liquid", {"R", "G", "B", "A"}, 0.0f));
      result.layers.push_back(filledLayer(width, height, "depth", {"Z"}, 1e10f));
      result.layers.push_back(filledLayer(width, height, "normal", {"X", "Y", "Z"}, 0.0f));
    }
    stats.readbackMilliseconds = millisecondsSince(readbackStart);
  });
  stats.totalMilliseconds = millisecondsSince(start);
  return result;
}

}  // namespace spindrift
