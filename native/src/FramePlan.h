#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "spindrift/RenderResult.h"

namespace spindrift {

/// Every pass a frame can run, in the order the recipe runs them.
enum class Pass {
  Background,
  OccluderDepth,
  LiquidMeshDepth,
  LightDepthLayers,
  LiquidShadow,
  Caustics,
  SkyOcclusion,
  LitTiles,  ///< the pixel tiles where the lights change the background (light.skip_unlit_tiles)
  LitBackground,
  SplashDepthLayers,
  AggregateDepthLayers,
  LiquidTiles,  ///< the pixel tiles that smoothing and refraction shade (liquid.skip_empty_tiles)
  Smoothing,
  RimNormals,       ///< the front normals near the aggregated body's silhouette (liquid.rim_normals)
  RaymarchSurface,  ///< liquid.surface = raymarch: six passes, timed by RaymarchSurface itself
  Refraction,
  RefractionFootprint,  ///< the background averaged over each liquid pixel's footprint
                        ///< (liquid.pixel_filter_width)
  FoamSceneDepth,
  FoamVisibility,
  FoamDepth,
  FoamThickness,
  FoamIntensity,
  FoamTiles,  ///< the pixel tiles that the foam's shadow, irradiance and blur shade (foam.skip_empty_tiles)
  FoamOcclusion,
  FoamBlur,
  Composite,
};

/// The pass's name in the stats ("splash_depth_layers").
const char* passName(Pass pass);

/// What a frame holds, as far as choosing its passes goes: known after the CPU preparation, before any GL
/// work.
struct FrameContents {
  std::size_t splashParticles = 0;      ///< Liquid particles in view drawn as splashes.
  std::size_t aggregateParticles = 0;   ///< Liquid particles in view drawn as the aggregated body.
  std::size_t foamParticles = 0;        ///< Secondary particles in view.
  std::string smoothing = "plane_fit";  ///< liquid.smoothing.
  std::size_t occluderMeshes = 0;       ///< Triangle meshes of solid geometry (files and in memory).
  bool liquidMesh = false;              ///< The liquid's own surface given as triangles.
  // What the caller reads back (`--layers`): a pass whose result reaches no wanted layer is not run.
  bool compositeWanted = true;
  bool liquidLayersWanted =
      true;                      ///< Any liquid layer: liquid, depth, normal, thickness, refraction split ...
  bool foamLayersWanted = true;  ///< Any foam layer.
  bool intermediateWanted = false;     ///< The depth layers before and after smoothing (`--intermediate`).
  std::string surface = "screen";      ///< liquid.surface.
  std::size_t lights = 0;              ///< Lights in the scene.
  std::size_t lightsSeeingLiquid = 0;  ///< Lights whose view of the liquid is drawn.
  std::size_t causticLights = 0;       ///< Of those, suns and spots (point lights cast no caustics).
  bool caustics = true;                ///< light.caustics.
  int skyOcclusionDirections = 16;     ///< light.sky_occlusion_directions.
  bool lightLayersWanted = true;       ///< Any of liquid_shadow, caustics, liquid_sky (`--layers`).
  /// Without a lamp that sees the liquid, the world's light alone still lights the background as the liquid
  /// lets it (light.sky_without_lamps, with the background's depth, a world that is not black and liquid).
  bool worldLightsAlone = false;
  bool foamCulling = true;         ///< foam.cull_hidden.
  bool skipEmptyTiles = true;      ///< liquid.skip_empty_tiles.
  bool skipEmptyFoamTiles = true;  ///< foam.skip_empty_tiles.
  bool skipUnlitTiles = true;      ///< light.skip_unlit_tiles.
  bool rimNormals = true;          ///< liquid.rim_normals.
  bool cameraInLiquid = false;     ///< The camera is under water: the body's front layer is not drawn.
  float pixelFilterWidth = 1.5f;   ///< liquid.pixel_filter_width.
};

/// Which passes a frame runs and, for each it does not, why. The wiring of the frame in one plain function,
/// so it can be read and tested without a GPU.
struct FramePlan {
  std::vector<Pass> passes;          ///< In the order they run.
  std::vector<SkippedPass> skipped;  ///< In pass order, with the reason.

  bool runs(Pass pass) const;
};

FramePlan planFrame(const FrameContents& contents);

}  // namespace spindrift
