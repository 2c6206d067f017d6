#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "prep/LiquidPreparation.h"
#include "prep/OccludedAggregates.h"
#include "spindrift/Camera.h"
#include "spindrift/Parameters.h"
#include "spindrift/Particles.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// A sphere around every liquid particle's drawn ellipsoid.
struct LiquidBounds {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;          ///< 0 when there is no liquid.
  float particleRadius = 0.0f;  ///< The largest liquid particle's.
  /// The smallest feature the liquid's surface holds: the particle radius, or Mantaflow's kernel radius r_m
  /// where the surface is Mantaflow's (liquid.mesh_kernel_radius above 1): its level set averages the
  /// particles over r_m, so it has no bump smaller (docs/liquid.md, "Light through the liquid", step 1).
  float detailRadius = 0.0f;
  glm::vec3 low{0.0f}, high{0.0f};  ///< A box around all the liquid drawn, tighter than the sphere when flat.
};

/// The side in texels of the lights' views: each texel as wide as the coarser of the camera's pixel where the
/// liquid comes nearest and the body's detail, LiquidBounds::detailRadius over light.texels_per_radius or
/// 1/128 of the view where that is finer (finer than both shows nothing the frame can use), within [32,
/// light.shadow_map_size]; light.shadow_map_size itself when light.texels_per_radius is 0.
int lightViewSize(const LiquidBounds& bounds, const Camera& camera, const LightParameters& parameters);

/// Pixels per sample along each axis of the sky occlusion (SkyOcclusionPass): what a point keeps of its sky
/// varies over the liquid's depth and size, not the pixel's, so a sample may stand for as many pixels as
/// span six radii of the liquid's detail (LiquidBounds::detailRadius) where the camera sees its centre,
/// within [4, 8]: 8 on a near camera's frame, 4 on a far one's (docs/frame-cost.md, session 59).
int skyOcclusionScale(const LiquidBounds& bounds, const Camera& camera);

LiquidBounds liquidBounds(const Particles& particles, const LiquidParameters& parameters);

/// How a light sees the liquid: a square camera that frames the liquid's bounds. A sun's view is a
/// perspective camera so far away (kSunDistanceInRadii bounding radii) that its rays are parallel to within
/// 1/kSunDistanceInRadii radians, which lets every liquid pass (impostors, smoothing) run unchanged for it.
struct LightView {
  Light light;
  Camera camera;
  bool sky = false;        ///< The view straight down that measures how deep a point lies below the surface.
  float texelSize = 0.0f;  ///< World size of a texel at the liquid's centre.
};

constexpr float kSunDistanceInRadii = 1000.0f;

/// The light's view of the liquid, or the reason there is none (a spot or point light inside the liquid's
/// bounds, or a spot whose cone misses them).
std::optional<LightView> lightViewOf(const Light& light, const LiquidBounds& bounds, int size,
                                     std::string* whyNot);

/// A view of the liquid from straight above (world +Z), for the sky light that submerged points lose.
LightView skyView(const LiquidBounds& bounds, int size);

/// The liquid as one light sees it: its own culling, splashes and aggregates together in `liquid.aggregates`
/// (a light sees one body).
struct LightPreparation {
  LightView view;
  LiquidPreparation liquid;
  std::size_t leftOut = 0;        ///< Particles hidden from both of the view's layers, not drawn.
  std::size_t columnThinned = 0;  ///< Of those, left out by light.column_particles (keepColumnEnds).
};

/// The views and ellipsoids of every light that sees the liquid, and of the sky; lights that do not are
/// listed in `skipped` with the reason.
struct LightingPreparation {
  std::vector<LightPreparation> lights;
  std::optional<LightPreparation> sky;
  LiquidBounds bounds;  ///< What every view frames.
  std::vector<std::string> skipped;
  int viewSize = 0;  ///< Side in texels of every view (lightViewSize).
  double milliseconds = 0.0;
};

/// The lights among `lighting.lights` that can cast caustics (suns and spots).
std::size_t causticLights(const LightingPreparation& lighting);

/// How many of a frame's lights see its liquid (those prepareLighting prepares a view for), and how many of
/// them can cast caustics: what the frame's plan needs, found from the liquid's bounds alone, before the
/// views are prepared.
struct LightsSeeing {
  std::size_t lights = 0;
  std::size_t causticLights = 0;
};
LightsSeeing lightsSeeingTheLiquid(const Particles& particles, const std::vector<Light>& lights,
                                   const LiquidParameters& parameters);

/// Prepares each light's view (and the sky's) of the liquid. `worldLightsAlone`: the sky's view is prepared
/// without lights too (FrameContents::worldLightsAlone). `frameCache`: the camera's, so that each particle is
/// shaped and Mantaflow's surface built and searched once per frame (prepareLiquid); `occlusion`: memory for
/// the lights' occlusion tests, kept from an earlier frame.
LightingPreparation prepareLighting(const Particles& particles, const Camera& camera,
                                    const std::vector<Light>& lights, bool worldLightsAlone,
                                    const Parameters& parameters, FrameLiquidCache* frameCache = nullptr,
                                    OcclusionWorkspace* occlusion = nullptr);

/// The lights' preparation kept for the frames after while nothing it depends on changes: the same particles
/// (`sameParticles`: LiquidCacheAcrossFrames::sameAsBefore), the same liquid and light parameters and
/// lights, and views of the same sides (a camera that comes nearer may want finer ones, lightViewSize).
/// A camera orbiting a paused frame in the viewport prepares no light's view again; the GL passes still draw
/// them, since what the camera sees of their light changes.
class LightingAcrossFrames {
 public:
  /// prepareLighting's result for this frame: the frame before's where it holds, else prepared anew.
  const LightingPreparation& forFrame(const Particles& particles, const Camera& camera,
                                      const std::vector<Light>& lights, bool worldLightsAlone,
                                      const Parameters& parameters, FrameLiquidCache* frameCache,
                                      bool sameParticles);
  /// Whether forFrame kept the frame before's.
  bool kept() const { return kept_; }

 private:
  std::optional<LightingPreparation> previous_;
  std::vector<Light> lights_;
  bool worldLightsAlone_ = false;
  LiquidParameters liquidParameters_;  // all of them: a light's view classifies and sizes its particles too
  LightParameters lightParameters_;
  OcclusionWorkspace occlusion_;
  bool kept_ = false;
};

}  // namespace spindrift
