#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "spindrift/Particles.h"

namespace spindrift {

/// One layer of the output, e.g. "composite" with channels R, G, B, A. Pixels are interleaved 32-bit floats,
/// top row first, linear colour, premultiplied alpha.
struct ImageLayer {
  std::string name;
  std::vector<std::string> channels;
  std::vector<float> pixels;

  std::size_t channelCount() const { return channels.size(); }
};

struct PassTiming {
  std::string name;
  double gpuMilliseconds = 0.0;  ///< From a GL_TIME_ELAPSED query around the pass.
  double cpuMilliseconds = 0.0;  ///< Wall time of the calls that issued the pass.
  /// Samples the pass's draws wrote (GL_SAMPLES_PASSED: fragments that passed the depth test and were not
  /// discarded), all its draws together: a full-screen draw writes every pixel once, the impostors' the
  /// fragments that won their depth test when drawn.
  std::uint64_t samplesPassed = 0;
};

struct SkippedPass {
  std::string name;
  std::string reason;
};

/// What the liquid pipeline found in a frame.
struct LiquidFrameStats {
  std::size_t splashParticles = 0;     ///< Drawn as spheres.
  std::size_t aggregateParticles = 0;  ///< Shaped as ellipsoids (drawn, or left out as hidden).
  std::size_t isotropicInterior = 0;   ///< Aggregates deep inside the body, drawn without anisotropy.
  float fullNeighbours = 0.0f;  ///< Neighbours within R of a particle inside the body (90th percentile).
  /// Yu and Turk's N_epsilon as applied to the frame (liquid.anisotropy_min_neighbours, lowered by
  /// liquid.anisotropy_min_neighbour_fraction for a coarsely sampled body).
  float minNeighboursApplied = 0.0f;
  /// The density of an interior particle, rho_0, from a sample of the whole frame's liquid: a particle is a
  /// splash below liquid.splash_density_threshold times it. 0 with liquid.layers = merged.
  float restDensity = 0.0f;
  /// liquid.relax_surface: the particles on the body's surface, those raised onto the smooth surface through
  /// their neighbours, the spacing it measured, and why it did nothing (empty when it ran;
  /// "liquid.relax_surface is off" or "Mantaflow's surface" when not asked to).
  std::size_t surfaceParticles = 0;
  std::size_t surfaceRaised = 0;
  float surfaceSpacing = 0.0f;
  std::string surfaceRelaxationNotApplied;
  bool surfaceRelaxationKept = false;  ///< The frame before's, for the same particles (liquid.reuse_shapes).
  double surfaceRelaxationMilliseconds = 0.0;
  std::size_t culled = 0;  ///< Outside the view frustum.
  /// In the frustum, but the background's solids hide them wholly (liquid.drop_hidden_interior): not shaped,
  /// not drawn.
  std::size_t hiddenBehindSolids = 0;
  std::size_t splashesAbsorbed = 0;  ///< Splashes below Mantaflow's surface: not drawn.
  /// Aggregates left out because they lie inside the union of the others (liquid.drop_hidden_interior).
  std::size_t hiddenInteriorDropped = 0;         ///< Aggregates hidden from both depth layers: not drawn.
  std::size_t hiddenInteriorFrontLayerOnly = 0;  ///< Their far half hidden: drawn into the front layer only.
  std::size_t hiddenInteriorBackLayerOnly = 0;   ///< Their near half hidden: drawn into the back layer only.
  std::string hiddenInteriorNotApplied;  ///< Why none were left out this frame, if something ruled it out.
  double hiddenInteriorMilliseconds = 0.0;
  std::size_t occludedFromFront = 0;  ///< Aggregates the view hides from the front layer (others cover them).
  std::size_t occludedFromBack = 0;   ///< Likewise from the back layer.
  std::size_t occludedDropped = 0;    ///< Hidden by the view from both layers: not drawn.
  /// Pixels of the kept aggregates' rectangles (once per layer each is drawn into): where the impostor pass
  /// could draw them, and where it does (their shown rectangles; docs/architecture.md).
  std::uint64_t occludedReachPixels = 0;
  std::uint64_t occludedShownPixels = 0;
  double occlusionMilliseconds = 0.0;
  std::size_t liquidPixels = 0;
  /// The 16 × 16 pixel tiles that smoothing, its normals and the refraction shaded, of `tiles` in the frame
  /// (liquid.skip_empty_tiles; both 0 when it is off).
  std::size_t tilesShaded = 0;
  std::size_t tiles = 0;
  std::size_t raysWithSecondBody =
      0;  ///< Rays that went on into a second body (third and fourth refraction).
  std::size_t totalInternalReflections = 0;
  /// Paths whose march inside a body left the screen; their unseen rest is estimated from the thickness.
  std::size_t exitsOffScreen = 0;
  /// Paths whose march inside a body passed behind a solid that hides the liquid (a tank's near wall): they
  /// end on a submerged surface no view shows, their unseen rest estimated from the thickness.
  std::size_t exitsBehindSolids = 0;
  /// The camera is inside the aggregated body: the frame is seen from under water.
  bool cameraInLiquid = false;
  /// Empty where the aggregates' front depth layer was drawn and smoothed; else what was left out of it and
  /// why: not drawn under water (no pass reads it: the body starts at the near plane), not smoothed under a
  /// ray-marched surface (which replaces it).
  std::string frontLayerSkipped;
  /// Rays with a second body, by order: splash>splash, splash>aggregate, aggregate>splash,
  /// aggregate>aggregate.
  std::size_t orders[4] = {0, 0, 0, 0};
  /// Empty where the particles' shapes from the frame before were kept (liquid.reuse_shapes: the same
  /// particles and liquid parameters); else why they were not ("the particles changed", ...).
  std::string shapesNotKept;
  double neighbourMilliseconds = 0.0;
  double anisotropyMilliseconds = 0.0;
};

/// What the ray-marched surface did in a frame (liquid.surface = raymarch; all zero otherwise).
struct RaymarchFrameStats {
  bool enabled = false;
  bool adaptiveStepping = true;      ///< liquid.raymarch_stepping was adaptive (else uniform).
  std::size_t densityParticles = 0;  ///< Liquid particles in the GPU neighbour grid.
  std::size_t gridCells = 0;         ///< Cells of the binary density grid.
  std::size_t raysCast = 0;
  std::size_t hits = 0;        ///< Rays that found the iso-surface.
  std::size_t totalSteps = 0;  ///< Marching steps of all rays: skips and density samples.
  double averageStepsPerRay = 0.0;
  double densityEvaluationsPerRay = 0.0;     ///< Bisection included.
  double refinementEvaluationsPerRay = 0.0;  ///< The bisection's density evaluations alone.
  double particlesVisitedPerRay = 0.0;  ///< Particles read by the density evaluations (neighbour search).
  /// Screen tiles cast at full, half and quarter resolution, and tiles without liquid.
  std::size_t tiles[4] = {0, 0, 0, 0};
};

/// What the foam pipeline found in a frame.
struct FoamFrameStats {
  std::size_t sprayParticles = 0;  ///< In view, by type.
  std::size_t surfaceParticles = 0;
  std::size_t bubbleParticles = 0;
  std::size_t culled = 0;              ///< Outside the view frustum.
  std::size_t hiddenBehindSolids = 0;  ///< In view but hidden by solids over the whole sprite: not drawn.
  std::size_t hiddenUnderLiquid = 0;   ///< Deeper under the liquid than foam.attenuation_distance: not drawn.
  std::size_t subPixel = 0;    ///< In view, holding no pixel's centre (foam.cull_sub_pixel): not drawn.
  std::size_t foamPixels = 0;  ///< Pixels with foam (intensity > 0).
  std::size_t occlusionEstimates = 0;  ///< SSAO estimates: foam pixels, or foam.occlusion_block blocks.
  double aoSamplesPerPixel = 0.0;      ///< Mean SSAO samples per foam pixel, all passes together.
  std::size_t lights = 0;              ///< The scene's lights that lit the foam (foam.lit_by_lights).
  /// The 16 × 16 pixel tiles that the shadow, irradiance and blur shaded, of `tiles` in the frame
  /// (foam.skip_empty_tiles; both 0 when it is off).
  std::size_t tilesShaded = 0;
  std::size_t tiles = 0;
};

/// What the light through the liquid found in a frame.
struct LightFrameStats {
  std::size_t lights = 0;              ///< In the scene.
  std::size_t lightsSeeingLiquid = 0;  ///< Whose view of the liquid was drawn.
  bool caustics = false;               ///< Whether any light's caustics were splatted.
  bool lightPasses = false;            ///< Whether the background had Cycles' light passes.
  /// CPU preparation of the lights' views; not in prepare_ms, as it runs while the GL thread draws the
  /// camera's surface.
  double prepareMilliseconds = 0.0;
  int viewSize = 0;  ///< Side in texels of the lights' views (light.texels_per_radius).
  /// The views were the frame before's, kept with their ellipsoids: the same particles, liquid and light
  /// parameters, lights and view sides (liquid.reuse_shapes).
  bool viewsKept = false;
  /// No lamp sees the liquid and the world's light alone lit the background as the liquid lets it: the sky's
  /// passes ran without a lamp's (light.sky_without_lamps).
  bool worldAlone = false;
  std::size_t viewParticles = 0;  ///< Liquid particles shaped for the lights' and the sky's views, summed.
  std::size_t viewParticlesLeftOut = 0;  ///< Of those, hidden from both layers of their view: not drawn.
  /// Of those left out, the ones a view of a body few particles deep did not keep in any texel column
  /// (light.column_particles).
  std::size_t viewParticlesColumnThinned = 0;
  /// Pixel tiles the lit background shaded, of `tiles`: those where a light's shadow or caustics or the sky
  /// light the liquid takes change a pixel (light.skip_unlit_tiles); the rest keep the background.
  std::size_t tilesShaded = 0;
  std::size_t tiles = 0;
  /// Pixels per sample along each axis of the sky occlusion, 4 to 8 by the camera's distance
  /// (skyOcclusionScale); 0 when it did not run.
  int skyOcclusionScale = 0;
};

/// The cost a Renderer pays once: the GL context, made while it is constructed, and the shader programs,
/// built on its GL thread while the first frame's particles are read and prepared.
struct SetupStats {
  double milliseconds = 0.0;  ///< From the Renderer's construction until its programs were built.
  int programsCompiled = 0;   ///< Shader programs compiled from source.
  int programsFromCache = 0;  ///< Loaded from the program binary cache (docs/architecture.md).
  int programsRejected = 0;   ///< Cache files that were corrupt or refused by the driver, then rebuilt.
};

/// What a frame cost and contained; `--stats` writes it as JSON.
struct FrameStats {
  int frame = 0;
  int width = 0;
  int height = 0;
  std::string glRenderer;
  std::string glVersion;
  ParticleCounts counts;  ///< Everything the sources held, by kind.
  LiquidFrameStats liquid;
  FoamFrameStats foam;
  LightFrameStats light;
  RaymarchFrameStats raymarch;
  double loadMilliseconds = 0.0;     ///< Reading particle files.
  double prepareMilliseconds = 0.0;  ///< CPU preparation: culling and packing.
  double readbackMilliseconds = 0.0;
  double totalMilliseconds = 0.0;  ///< Wall time of the whole frame, loading included.
  /// The first frame of a Renderer also carries its one-time setup; later frames carry zeros, so a sequence's
  /// per-frame cost is its frames' totals. The setup's programs are built beside the first frame's loading
  /// and preparation, which they slow a little; a first frame whose preparation is done before them waits,
  /// and that wait is part of its totalMilliseconds.
  bool firstFrame = true;
  SetupStats setup;
  std::vector<PassTiming> passes;
  std::vector<SkippedPass> skipped;

  nlohmann::json toJson() const;
};

struct RenderResult {
  int width = 0;
  int height = 0;
  std::vector<ImageLayer> layers;
  FrameStats stats;

  /// The layer with this name, or nullptr.
  const ImageLayer* layer(const std::string& name) const;
};

}  // namespace spindrift
