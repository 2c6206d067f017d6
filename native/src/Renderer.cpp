#include "spindrift/Renderer.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <future>
#include <optional>
#include <utility>

#include <glm/vector_relational.hpp>

#include "FramePlan.h"
#include "FrameStatsRecording.h"
#include "LiquidLighting.h"
#include "RaymarchSurface.h"
#include "Readback.h"
#include "gl/GlThread.h"
#include "gl/PassTimer.h"
#include "gl/QueryGlLimits.h"
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
#include "passes/FoamVisibilityPass.h"
#include "passes/FrameUniforms.h"
#include "passes/OccluderDepthPass.h"
#include "passes/PixelTilePass.h"
#include "passes/RefractionFootprintPass.h"
#include "passes/RefractionPass.h"
#include "passes/RimNormalsPass.h"
#include "prep/BackgroundCache.h"
#include "prep/FoamPreparation.h"
#include "prep/FrameLiquidCache.h"
#include "prep/HiddenInterior.h"
#include "prep/LayerOrder.h"
#include "prep/LightViews.h"
#include "prep/LiquidPreparation.h"
#include "prep/MantaflowSurface.h"
#include "prep/RaymarchPreparation.h"
#include "prep/SurfaceRelaxation.h"
#include "spindrift/Error.h"
#include "spindrift/Limits.h"

namespace spindrift {
namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Every GL object of the frame; made, used and destroyed on the GL thread.
struct FramePipeline {
  explicit FramePipeline(const std::filesystem::path& shaderDirectory)
      : shaders(shaderDirectory, ProgramCache::forCurrentContext()) {}

  ShaderLibrary shaders;
  FrameUniformBuffer frameUniforms;
  PassTimer timer;
  BackgroundPass background{shaders};
  LiquidLighting lighting{shaders};
  OccluderDepthPass occluderDepth{shaders};
  OccluderDepthPass liquidMeshDepth{shaders};
  EllipsoidImpostorPass splashImpostors{shaders};
  EllipsoidImpostorPass aggregateImpostors{shaders};
  PixelTilePass liquidTiles{shaders};
  PixelTilePass foamTiles{shaders};
  DepthSmoothingPass frontSmoothing{shaders};
  DepthSmoothingPass backSmoothing{shaders};
  RimNormalsPass rimNormals{shaders};
  RaymarchSurface raymarch{shaders};
  RefractionPass refraction{shaders};
  RefractionFootprintPass refractionFootprint{shaders};
  FoamSceneDepthPass foamSceneDepth{shaders};
  FoamVisibilityPass foamVisibility{shaders};
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

// The eye depths of the layers drawn, for the tiles that hold liquid.
std::vector<const Texture2D*> eyeDepthsOf(const std::optional<SurfaceLayers>& splashes,
                                          const std::optional<SurfaceLayers>& aggregates) {
  std::vector<const Texture2D*> eyeDepths;
  for (const std::optional<SurfaceLayers>* layers : {&splashes, &aggregates})
    if (*layers) {
      eyeDepths.push_back(&(*layers)->front.eyeDepth);
      eyeDepths.push_back(&(*layers)->back.eyeDepth);
    }
  return eyeDepths;
}

// A result with the frame's size and what the stats know before any work.
RenderResult emptyResult(int frame, int width, int height, const Particles& particles) {
  RenderResult result;
  result.width = width;
  result.height = height;
  result.stats.frame = frame;
  result.stats.width = width;
  result.stats.height = height;
  result.stats.counts = countByKind(particles);
  return result;
}

// An in-memory background image must have the camera's size; BackgroundCache resamples only files.
void requireCameraSize(const FloatImage& image, int channels, const char* what, int width, int height) {
  if (image.width != width || image.height != height || image.channels != channels ||
      image.pixels.size() != std::size_t(width) * height * channels)
    throw Error(std::string(what) + ": expected " + std::to_string(width) + "x" + std::to_string(height) +
                "x" + std::to_string(channels) + " floats (the camera's size), got " +
                std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                std::to_string(image.channels));
}

}  // namespace

// In-memory inputs of a frame, by pointer, beside those loaded from the scene's files.
struct Renderer::FrameExtras {
  std::vector<const TriangleMesh*> occluders;
  const TriangleMesh* liquidMesh = nullptr;
  const FloatImage* backgroundColor = nullptr;
  const FloatImage* backgroundDepth = nullptr;
};

struct Renderer::Impl {
  GlThread glThread;
  std::unique_ptr<FramePipeline> pipeline;  // Lives on glThread; reset there before the thread ends.
  BackgroundCache backgroundCache;
  LiquidCacheAcrossFrames liquidCache;
  SurfaceRelaxationAcrossFrames surfaceRelaxation;
  LightingAcrossFrames lightingCache;
  OcclusionWorkspace occlusionWorkspace;  // the camera's occlusion test's memory, kept for the next frame
  GlLimits glLimits;
  bool intermediateLayers = false;
  LayerSelection layers;
  bool firstFrame = true;
  SetupStats setup;  // Written by the pipeline's setup on glThread; read after pipelineReady.
  std::shared_future<void> pipelineReady;  // Carries the setup's Error, if any, to every frame.
  // In-memory backgrounds change every frame: each gets its own upload generation, apart from the cache's.
  std::uint64_t hostBackgroundGeneration = std::uint64_t(1) << 63;

  ~Impl() {
    glThread.run([this] { pipeline.reset(); });
  }
};

Renderer::Renderer() : Renderer(findShaderDirectory()) {}

Renderer::Renderer(const std::filesystem::path& shaderDirectory) {
  const Clock::time_point start = Clock::now();
  requireShaderSources(shaderDirectory);
  impl_ = std::make_unique<Impl>();
  impl_->glLimits = impl_->glThread.run(queryGlLimits);
  // The programs are linked or loaded from the cache while the first frame's particles are read and prepared
  // on this thread (docs/frame-cost.md, "Setup beside the first frame"); the first GL work waits for them,
  // and an Error in building them comes out of every frame.
  Impl* impl = impl_.get();  // ~Impl waits for this task (the GL thread runs its work in order)
  impl->pipelineReady = impl->glThread
                            .submit([impl, start, shaderDirectory] {
                              impl->pipeline = std::make_unique<FramePipeline>(shaderDirectory);
                              const ProgramCacheCounts& programs = impl->pipeline->shaders.cacheCounts();
                              impl->setup.programsCompiled = programs.compiled;
                              impl->setup.programsFromCache = programs.loaded;
                              impl->setup.programsRejected = programs.rejected;
                              impl->setup.milliseconds = millisecondsSince(start);
                            })
                            .share();
}

Renderer::~Renderer() = default;

void Renderer::setIntermediateLayers(bool enabled) {
  impl_->intermediateLayers = enabled;
}
void Renderer::setLayers(const std::vector<std::string>& names) {
  impl_->layers = LayerSelection(names);
}

std::string Renderer::glRenderer() const {
  return impl_->glThread.renderer();
}
std::string Renderer::glVersion() const {
  return impl_->glThread.version();
}
const GlLimits& Renderer::glLimits() const {
  return impl_->glLimits;
}

// Everything that could make a frame fail halfway or allocate without bound is checked first, with an
// error that names the limit (docs/reliability.md, "Limits").
void Renderer::checkFrame(const Scene& scene, std::size_t particleCount) const {
  const Camera& camera = scene.camera;
  validateCamera(camera);
  checkImageFitsGl(impl_->glLimits, camera.width, camera.height, "camera: the image");
  requireMemory(std::uint64_t(camera.width) * std::uint64_t(camera.height) * kFrameBytesPerPixel +
                    std::uint64_t(particleCount) * kPreparationBytesPerParticle,
                "a " + std::to_string(camera.width) + "x" + std::to_string(camera.height) + " frame of " +
                    std::to_string(particleCount) + " particles");
}

RenderResult Renderer::renderFrame(const Scene& scene, int frame) {
  return renderFrame(scene, frame, FrameInputs{});
}

RenderResult Renderer::renderFrame(const Scene& scene, int frame, const FrameInputs& inputs) {
  const Clock::time_point start = Clock::now();
  checkFrame(scene, 0);  // Before any file is read; renderParticles checks again with the particle count.
  ParticleCounts counts;
  Particles particles = loadParticles(scene, frame, &counts);
  const std::size_t droppedFromFiles = counts.droppedInvalid;
  const std::size_t droppedInMemory = appendValidParticles(particles, inputs.particles);
  counts = countByKind(particles);
  counts.droppedInvalid = droppedFromFiles + droppedInMemory;
  for (std::size_t i = 0; i < inputs.occluders.size(); ++i)
    inputs.occluders[i].validate("occluders[" + std::to_string(i) + "]");
  if (inputs.liquidMesh) inputs.liquidMesh->validate("liquid_mesh");
  FrameInputs files;
  loadMeshes(scene, frame, files);
  const double loadMilliseconds = millisecondsSince(start);
  FrameExtras extras;
  for (const TriangleMesh& mesh : files.occluders)
    extras.occluders.push_back(&mesh);
  for (const TriangleMesh& mesh : inputs.occluders)
    extras.occluders.push_back(&mesh);
  extras.liquidMesh = inputs.liquidMesh  ? &*inputs.liquidMesh
                      : files.liquidMesh ? &*files.liquidMesh
                                         : nullptr;
  extras.backgroundColor = inputs.backgroundColor ? &*inputs.backgroundColor : nullptr;
  extras.backgroundDepth = inputs.backgroundDepth ? &*inputs.backgroundDepth : nullptr;
  RenderResult result = renderPrepared(scene, particles, frame, extras);
  result.stats.counts = counts;
  result.stats.loadMilliseconds = loadMilliseconds;
  result.stats.totalMilliseconds = millisecondsSince(start);
  return result;
}

// The frame, top to bottom, as the liquid paper's figure 4 draws it: prepare the particles on the CPU (split
// into splashes and aggregates, anisotropic ellipsoids; foam culled and packed) and plan the passes, then on
// the GL thread the background, the front and back depth layers of splashes and of aggregates and the
// smoothing of the aggregate layers (while the CPU prepares the lights' views), the light through the liquid
// onto the background, refraction, the foam paper's seven passes (figure 2), and the composite; then read
// the layers back. A pass the plan leaves out is not run, and the
// stats say why (FramePlan.cpp).
RenderResult Renderer::renderParticles(const Scene& scene, const Particles& particles, int frame) {
  return renderPrepared(scene, particles, frame, FrameExtras{});
}

RenderResult Renderer::renderPrepared(const Scene& scene, const Particles& givenParticles, int frame,
                                      const FrameExtras& extras) {
  const Clock::time_point start = Clock::now();
  const Camera& camera = scene.camera;
  const LiquidParameters& liquidParameters = scene.parameters.liquid;
  const FoamParameters& foamParameters = scene.parameters.foam;
  const int width = camera.width, height = camera.height;
  checkFrame(scene, givenParticles.size());
  validateParticles(givenParticles);
  // Every view of the frame (the camera's, each light's, the sky's) draws the same relaxed liquid.
  SurfaceRelaxationStats relaxation;
  const Particles& particles =
      impl_->surfaceRelaxation.forFrame(givenParticles, liquidParameters, relaxation);
  // A Mantaflow liquid is clipped to its domain's box, as Mantaflow closes its mesh at the walls.
  const DomainBox* domainBox = nullptr;
  for (const ParticleSource& source : scene.particles)
    if (source.role == ParticleRole::Liquid && source.domainBox && !domainBox) domainBox = &*source.domainBox;
  RenderResult result = emptyResult(frame, width, height, particles);
  result.stats.glRenderer = glRenderer();
  result.stats.glVersion = glVersion();
  FrameStats& stats = result.stats;
  recordSurfaceRelaxation(relaxation, stats.liquid);

  const Clock::time_point prepareStart = Clock::now();
  // Under water is decided on every aggregate; dropHiddenAggregates below leaves a body that reaches the
  // camera's near plane whole, so the ellipsoids around the camera are still drawn.
  BackgroundImages backgroundImages = impl_->backgroundCache.load(scene.background, frame, width, height);
  if (extras.backgroundColor) {
    requireCameraSize(*extras.backgroundColor, 4, "background colour", width, height);
    backgroundImages.color = extras.backgroundColor;
    backgroundImages.lightPasses = nullptr;  // The file's light passes belong to the file's image.
  }
  if (extras.backgroundDepth) {
    requireCameraSize(*extras.backgroundDepth, 1, "background depth", width, height);
    backgroundImages.eyeDepth = extras.backgroundDepth;
  }
  if (extras.backgroundColor || extras.backgroundDepth)
    backgroundImages.generation = ++impl_->hostBackgroundGeneration;
  // The solids the impostor passes test against: the background's depth and the occluder triangles. The
  // particles they hide wholly are not shaped, and those they hide from the view are not drawn.
  std::optional<SolidDepthTiles> solids;
  if (liquidParameters.drop_hidden_interior) {
    solids.emplace(camera);
    if (backgroundImages.eyeDepth) solids->addDepthImage(*backgroundImages.eyeDepth);
    for (const TriangleMesh* mesh : extras.occluders)
      solids->addTriangles(*mesh);
  }
  const SolidDepthTiles* frameSolids = solids ? &*solids : nullptr;
  // Without a lamp the world still lights the background where it has solids to light and liquid to take
  // some of that light, which the sky's view then finds (docs/liquid.md, "The world's light alone").
  const bool worldMayLight = scene.parameters.light.sky_without_lamps &&
                             (glm::any(glm::greaterThan(backgroundImages.fallbackColor, glm::vec3(0.0f))) ||
                              backgroundImages.environment != nullptr) &&
                             (backgroundImages.eyeDepth != nullptr || !extras.occluders.empty());
  // What the camera's and the lights' views share, kept for the next frame while the particles and the
  // liquid parameters stay the same (liquid.reuse_shapes).
  FrameLiquidCache* shared =
      impl_->liquidCache.forFrame(particles, liquidParameters, !scene.lights.empty() || worldMayLight);
  stats.liquid.shapesNotKept = impl_->liquidCache.whyNotKept();
  LiquidPreparation liquid = prepareLiquid(particles, camera, liquidParameters, shared, frameSolids);
  const bool cameraInLiquid = aggregatesContain(liquid.aggregates, camera.position(), domainBox);
  const float radius = typicalLiquidRadius(particles);
  const FoamPreparation foam = prepareFoam(particles, camera, foamParameters);
  std::optional<RaymarchPreparation> raymarch;
  if (liquidParameters.surface == "raymarch")
    raymarch.emplace(prepareRaymarch(liquid, camera, radius, liquidParameters, domainBox));
  if (liquidParameters.drop_hidden_interior) {
    const HiddenInteriorResult hidden =
        dropHiddenAggregates(liquid, camera, domainBox, frameSolids, &impl_->occlusionWorkspace);
    stats.liquid.hiddenInteriorDropped = hidden.dropped;
    stats.liquid.hiddenInteriorFrontLayerOnly = hidden.split.frontOnly;
    stats.liquid.hiddenInteriorBackLayerOnly = hidden.split.backOnly;
    stats.liquid.hiddenInteriorNotApplied = hidden.notApplied;
    stats.liquid.hiddenInteriorMilliseconds = hidden.milliseconds;
    stats.liquid.occludedFromFront = hidden.occluded.hiddenFromFront;
    stats.liquid.occludedFromBack = hidden.occluded.hiddenFromBack;
    stats.liquid.occludedDropped = hidden.occluded.dropped;
    stats.liquid.occludedReachPixels = hidden.occluded.reachPixels;
    stats.liquid.occludedShownPixels = hidden.occluded.shownPixels;
    stats.liquid.occlusionMilliseconds = hidden.occluded.milliseconds;
  }
  if (backgroundImages.environment)
    checkImageFitsGl(impl_->glLimits, backgroundImages.environment->width,
                     backgroundImages.environment->height,
                     "background.environment " + pathForFrame(scene.background.environment, frame).string());
  stats.prepareMilliseconds = millisecondsSince(prepareStart);
  recordPreparation(liquid, foam, stats);
  stats.liquid.cameraInLiquid = cameraInLiquid;
  // The aggregates' front layer feeds the refraction's first surface alone. Under water the body starts at
  // the near plane and a path that leaves it is followed into splashes only, so no pass reads that layer: it
  // is neither drawn nor smoothed (docs/liquid.md, "A camera under water"). A ray-marched surface replaces it
  // after it is drawn.
  if (raymarch) {
    stats.liquid.frontLayerSkipped = "not smoothed: the ray-marched surface replaces it";
  } else if (cameraInLiquid) {
    keepBackLayerOnly(liquid.aggregates, liquid.aggregateLayers);
    stats.liquid.frontLayerSkipped =
        "not drawn: the camera is under water, where the body starts at the near plane";
  }
  const bool smoothFront = stats.liquid.frontLayerSkipped.empty();
  const LayerSelection& layers = impl_->layers;
  FrameContents contents{liquid.splashes.size(),     liquid.aggregates.size(),   foam.instances.size(),
                         liquidParameters.smoothing, extras.occluders.size(),    extras.liquidMesh != nullptr,
                         layers.wantsComposite(),    layers.wantsLiquidLayers(), layers.wantsFoamLayers(),
                         impl_->intermediateLayers,  liquidParameters.surface};
  contents.rimNormals = liquidParameters.rim_normals;
  contents.pixelFilterWidth = liquidParameters.pixel_filter_width;
  contents.cameraInLiquid = cameraInLiquid;
  contents.lights = scene.lights.size();
  contents.foamCulling = foamParameters.cull_hidden;
  contents.skipEmptyTiles = liquidParameters.skip_empty_tiles;
  contents.skipEmptyFoamTiles = foamParameters.skip_empty_tiles;
  contents.skipUnlitTiles = scene.parameters.light.skip_unlit_tiles;
  // Which lights see the liquid is known from its bounds; their views are prepared below, while the GL
  // thread draws the camera's surface.
  const LightsSeeing seeing = lightsSeeingTheLiquid(particles, scene.lights, liquidParameters);
  contents.lightsSeeingLiquid = seeing.lights;
  // Liquid the sky's view can draw (none when the frame holds foam alone: prepareLighting then has no view).
  contents.worldLightsAlone =
      seeing.lights == 0 && worldMayLight && liquidBounds(particles, liquidParameters).radius > 0.0f;
  contents.causticLights = seeing.causticLights;
  contents.caustics = scene.parameters.light.caustics;
  contents.skyOcclusionDirections = scene.parameters.light.sky_occlusion_directions;
  contents.lightLayersWanted = layers.wantsLightLayers();
  const FramePlan plan = planFrame(contents);
  stats.skipped = plan.skipped;
  stats.light.caustics = plan.runs(Pass::Caustics);

  impl_->pipelineReady.get();
  stats.firstFrame = std::exchange(impl_->firstFrame, false);
  if (stats.firstFrame) stats.setup = impl_->setup;
  FramePipeline& pipeline = *impl_->pipeline;
  auto timed = [&](Pass pass, auto&& issuePass) {
    return timePass(pipeline.timer, passName(pass), issuePass);
  };
  IntermediateLayers intermediate(impl_->intermediateLayers);
  // The camera's surface first: its background, its depth layers and their smoothing test against the
  // solids' depth alone, which no light changes, so the GL thread draws them while this thread prepares the
  // lights' views (docs/frame-cost.md, session 45).
  std::optional<BackgroundData> unlit;
  std::optional<SurfaceLayers> splashes, aggregates;
  std::optional<PixelTiles> liquidTiles;
  std::future<void> surfaceDrawn = impl_->glThread.submit([&] {
    pipeline.frameUniforms.update(camera);
    const BackgroundData resolved =
        timed(Pass::Background, [&] { return pipeline.background.run(backgroundImages, width, height); });
    // Solid geometry handed as triangles joins the background's depth, so every later pass that tests against
    // solids sees it; the liquid's own mesh stands in for (or joins) background.liquid_depth.
    auto meshDepth = [&](Pass pass, OccluderDepthPass& prepass,
                         const std::vector<const TriangleMesh*>& meshes,
                         const Texture2D* start) -> const Texture2D* {
      if (!plan.runs(pass)) return start;
      return &timed(pass, [&] { return prepass.run(meshes, start, width, height); }).eyeDepth;
    };
    const Texture2D& solidDepth =
        *meshDepth(Pass::OccluderDepth, pipeline.occluderDepth, extras.occluders, &resolved.eyeDepth);
    const Texture2D* liquidDepth = meshDepth(Pass::LiquidMeshDepth, pipeline.liquidMeshDepth,
                                             {extras.liquidMesh}, resolved.liquidEyeDepth);
    unlit.emplace(BackgroundData{resolved.color, solidDepth, resolved.environment, resolved.fallbackColor,
                                 liquidDepth, resolved.lightPasses});
    if (plan.runs(Pass::SplashDepthLayers)) {
      splashes.emplace(timed(Pass::SplashDepthLayers, [&] {
        return pipeline.splashImpostors.run(liquid.splashes, {}, &*unlit, camera, domainBox);
      }));
      intermediate.keep(*splashes, "splash");
    }
    if (plan.runs(Pass::AggregateDepthLayers)) {
      aggregates.emplace(timed(Pass::AggregateDepthLayers, [&] {
        return pipeline.aggregateImpostors.run(liquid.aggregates, liquid.aggregateLayers, &*unlit, camera,
                                               domainBox);
      }));
      intermediate.keep(*aggregates, "aggregate");
    }
    // The pixel tiles that hold a pixel of any layer: smoothing and refraction shade only these.
    if (plan.runs(Pass::LiquidTiles))
      liquidTiles.emplace(timed(Pass::LiquidTiles, [&] {
        return pipeline.liquidTiles.run(eyeDepthsOf(splashes, aggregates), width, height);
      }));
    const PixelTiles* withLiquid = liquidTiles ? &*liquidTiles : nullptr;
    if (plan.runs(Pass::Smoothing)) {
      aggregates.emplace(timed(Pass::Smoothing, [&] {
        return SurfaceLayers{smoothFront
                                 ? pipeline.frontSmoothing.run(aggregates->front, radius, false,
                                                               liquidParameters, withLiquid, width, height)
                                 : aggregates->front,
                             pipeline.backSmoothing.run(aggregates->back, radius, true, liquidParameters,
                                                        withLiquid, width, height)};
      }));
      intermediate.keep(*aggregates, "aggregate_smoothed");
    }
    if (plan.runs(Pass::RimNormals)) {
      const RecomputedNormals rim = timed(Pass::RimNormals, [&] {
        return pipeline.rimNormals.run(*aggregates, unlit->eyeDepth, domainBox, radius, withLiquid, width,
                                       height);
      });
      aggregates.emplace(SurfaceLayers{DepthLayer{aggregates->front.eyeDepth, rim.normal}, aggregates->back});
    }
  });
  const LightingPreparation* preparedLighting = nullptr;
  try {
    preparedLighting =
        &impl_->lightingCache.forFrame(particles, camera, scene.lights, contents.worldLightsAlone,
                                       scene.parameters, shared, impl_->liquidCache.sameAsBefore());
  } catch (...) {
    surfaceDrawn.wait();  // it draws into this frame's locals
    throw;
  }
  const LightingPreparation& lighting = *preparedLighting;
  recordLighting(scene.lights.size(), lighting, backgroundImages.lightPasses != nullptr, stats.light);
  stats.light.viewsKept = impl_->lightingCache.kept();
  stats.light.worldAlone = plan.runs(Pass::LitBackground) && contents.worldLightsAlone;
  surfaceDrawn.get();

  impl_->glThread.run([&] {
    // Light through the liquid onto the background (shadows, caustics, submerged points), before anything
    // refracts or shows the background; LiquidLighting times its passes per light.
    std::optional<LitBackgroundData> lit;
    if (plan.runs(Pass::LitBackground))
      lit.emplace(pipeline.lighting.run(lighting, camera, *unlit, radius, scene.parameters,
                                        plan.runs(Pass::SkyOcclusion), plan.runs(Pass::LiquidShadow),
                                        plan.runs(Pass::LitTiles), pipeline.timer));
    const BackgroundData background = lit ? lit->background : *unlit;
    const PixelTiles* withLiquid = liquidTiles ? &*liquidTiles : nullptr;
    if (plan.runs(Pass::RaymarchSurface)) {  // times its six passes itself
      RaymarchSurface& surface = pipeline.raymarch;
      replaceFrontLayers(surface.run(*raymarch, splashes, aggregates, background, liquidParameters,
                                     pipeline.timer, width, height),
                         splashes, aggregates);
      if (impl_->intermediateLayers) intermediate.keep(surface.intermediateLayers());
      stats.raymarch = surface.statistics();
    }
    std::optional<LiquidData> liquidLayer;
    // Under water every pixel is liquid; a ray-marched front may reach pixels no particle layer covers.
    const PixelTiles* refractionTiles = cameraInLiquid || raymarch ? nullptr : withLiquid;
    if (plan.runs(Pass::Refraction))
      liquidLayer.emplace(timed(Pass::Refraction, [&] {
        return pipeline.refraction.run(splashes, aggregates, background, liquidParameters, cameraInLiquid,
                                       radius, domainBox, refractionTiles, width, height);
      }));
    if (plan.runs(Pass::RefractionFootprint))
      timed(Pass::RefractionFootprint, [&] {
        pipeline.refractionFootprint.run(*liquidLayer, background, liquidParameters.pixel_filter_width,
                                         refractionTiles);
      });

    // Foam (foam paper, figure 2): the solids' and the liquid's depth, the foam's nearest depth, its
    // thickness, intensity, shadow and irradiance, then blur and the foam layer. The plan runs all six or
    // none.
    std::optional<FoamLayerData> foamLayer;
    if (plan.runs(Pass::FoamDepth)) {
      const FoamSceneDepth sceneDepth = timed(Pass::FoamSceneDepth, [&] {
        return pipeline.foamSceneDepth.run(background, liquidLayer ? &liquidLayer->frontDepth : nullptr,
                                           width, height);
      });
      // Particles that no foam layer would show are left out of the sprite passes (foam.cull_hidden).
      std::optional<VisibleFoam> visible;
      if (plan.runs(Pass::FoamVisibility))
        visible.emplace(timed(Pass::FoamVisibility, [&] {
          return cullHiddenFoam(foam.instances, camera,
                                pipeline.foamVisibility.run(sceneDepth, foamParameters, width, height));
        }));
      if (visible) recordFoamCulling(*visible, stats.foam);
      const FoamSurfaceData foamSurface = timed(Pass::FoamDepth, [&] {
        return pipeline.foamDepth.run(visible ? visible->instances : foam.instances, sceneDepth, width,
                                      height);
      });
      const FoamThicknessData foamThickness = timed(Pass::FoamThickness, [&] {
        return pipeline.foamThickness.run(foamSurface, sceneDepth, foamParameters, width, height);
      });
      const FoamIntensityData foamIntensity = timed(Pass::FoamIntensity, [&] {
        return pipeline.foamIntensity.run(foamThickness, foamParameters, width, height);
      });
      // The tiles with a foam pixel (ι > 0): the shadow, irradiance and blur shade only these.
      std::optional<PixelTiles> foamTiles;
      if (plan.runs(Pass::FoamTiles))
        foamTiles.emplace(timed(Pass::FoamTiles, [&] {
          return pipeline.foamTiles.run({&foamIntensity.intensity}, width, height);
        }));
      const PixelTiles* withFoam = foamTiles ? &*foamTiles : nullptr;
      const FoamOcclusionData foamOcclusion = timed(Pass::FoamOcclusion, [&] {
        return pipeline.foamOcclusion.run(foamSurface, foamIntensity, sceneDepth, background, scene.lights,
                                          foamParameters, withFoam, width, height);
      });
      foamLayer.emplace(timed(Pass::FoamBlur, [&] {
        return pipeline.foamBlur.run(foamSurface, foamThickness, foamIntensity, foamOcclusion, foamParameters,
                                     withFoam, width, height);
      }));
    }
    std::optional<CompositeData> composite;
    if (plan.runs(Pass::Composite))
      composite.emplace(timed(Pass::Composite, [&] {
        return pipeline.composite.run(background, liquidLayer ? &*liquidLayer : nullptr,
                                      foamLayer ? &*foamLayer : nullptr, width, height);
      }));
    stats.passes = pipeline.timer.collect();

    const Clock::time_point readbackStart = Clock::now();
    if (liquidLayer) recordRefraction(pipeline.refraction.statistics(), stats.liquid);
    if (liquidTiles) {
      stats.liquid.tilesShaded = pipeline.liquidTiles.markedTiles();
      stats.liquid.tiles = std::size_t(pixelTilesAcross(width)) * std::size_t(pixelTilesDown(height));
    }
    if (foamLayer) {
      recordFoamOcclusion(pipeline.foamOcclusion.statistics(), stats.foam);
      stats.foam.lights = foamParameters.lit_by_lights ? scene.lights.size() : 0;
    }
    if (plan.runs(Pass::SkyOcclusion)) stats.light.skyOcclusionScale = pipeline.lighting.skyOcclusionScale();
    if (plan.runs(Pass::LitTiles)) {
      stats.light.tilesShaded = pipeline.lighting.litTilesShaded();
      stats.light.tiles = std::size_t(pixelTilesAcross(width)) * std::size_t(pixelTilesDown(height));
    }
    if (plan.runs(Pass::FoamTiles)) {
      stats.foam.tilesShaded = pipeline.foamTiles.markedTiles();
      stats.foam.tiles = std::size_t(pixelTilesAcross(width)) * std::size_t(pixelTilesDown(height));
    }
    readFrameLayers(composite ? &*composite : nullptr, liquidLayer ? &*liquidLayer : nullptr,
                    foamLayer ? &*foamLayer : nullptr, width, height, layers, result.layers);
    readLightLayers(lit ? &*lit : nullptr, !scene.lights.empty(), width, height, layers, result.layers);
    intermediate.appendTo(result.layers);
    stats.readbackMilliseconds = millisecondsSince(readbackStart);
  });
  stats.totalMilliseconds = millisecondsSince(start);
  return result;
}

}  // namespace spindrift
