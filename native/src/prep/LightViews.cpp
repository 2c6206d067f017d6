#include "prep/LightViews.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "prep/Anisotropy.h"
#include "prep/HiddenInterior.h"
#include "prep/LightColumns.h"

namespace spindrift {
namespace {

// The sky's view's resolution, in texels per particle radius before it is halved (see prepareLights).
constexpr float kSkyTexelsPerRadius = 3.0f;

// An up vector that is not parallel to the view direction.
glm::vec3 upFor(const glm::vec3& forward) {
  return std::abs(forward.z) < 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

// A square camera at `position` that looks at the bounds and frames them with a margin.
Camera framingCamera(const glm::vec3& position, const LiquidBounds& bounds, int size) {
  const glm::vec3 forward = bounds.centre - position;
  const float distance = glm::length(forward);
  const float halfAngle = std::asin(std::min(1.0f, 1.02f * bounds.radius / distance));
  Camera camera =
      Camera::lookAt(size, size, glm::degrees(2.0f * halfAngle), position, bounds.centre, upFor(forward));
  // Half the distance to the bounds: the impostor pass places each particle's quad at least 1 % beyond the
  // near plane, which must still lie in front of the particle.
  camera.nearClip = std::max(0.5f * (distance - 1.5f * bounds.radius), 1e-3f * distance);
  camera.farClip = distance + 1.5f * bounds.radius;
  return camera;
}

// World size of a view's texel at the liquid's centre (the views look at it).
float texelSizeAt(const Camera& camera, const LiquidBounds& bounds) {
  return camera.pixelSizeAt(glm::distance(camera.position(), bounds.centre));
}

// The sky's view finds how deep below the surface a point lies, which varies slowly, and what liquid a
// point's hemisphere holds: half the side of a view of kSkyTexelsPerRadius, whatever the lights' texels.
// Half the side of a 2-texel view left the floor just past a floating slab's edge 0.036 off the hemisphere
// integral (GLSkyOcclusion.FloorNearAFloatingSlabKeepsTheHemisphereIntegral).
int skyViewSide(const LiquidBounds& bounds, const Camera& camera, const LightParameters& parameters) {
  LightParameters skyParameters = parameters;
  skyParameters.texels_per_radius = kSkyTexelsPerRadius;
  const int side = lightViewSize(bounds, camera, skyParameters);
  return std::max(side / 2, std::min(32, side));
}

}  // namespace

LiquidBounds liquidBounds(const Particles& particles, const LiquidParameters& parameters) {
  glm::vec3 low(1e30f), high(-1e30f);
  float largestRadius = 0.0f;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.kinds[i] != ParticleKind::Liquid) continue;
    const glm::vec3& position = particles.positions[i];
    if (!std::isfinite(position.x + position.y + position.z) || !(particles.radii[i] > 0.0f)) continue;
    low = glm::min(low, position);
    high = glm::max(high, position);
    largestRadius = std::max(largestRadius, particles.radii[i]);
  }
  LiquidBounds bounds;
  if (largestRadius == 0.0f) return bounds;
  bounds.centre = 0.5f * (low + high);
  // A drawn ellipsoid reaches its grown longest semi-axis from its centre, and anisotropy smoothing can move
  // that centre by up to lambda times the neighbourhood.
  const float reach =
      (std::max(1.0f, parameters.max_ellipsoid_scale) + largestSurfaceOffset(parameters)) * largestRadius +
      parameters.anisotropy_smoothing * parameters.neighbour_radius * largestRadius;
  bounds.radius = 0.5f * glm::length(high - low) + reach;
  bounds.particleRadius = largestRadius;
  bounds.detailRadius = std::max(1.0f, parameters.mesh_kernel_radius) * largestRadius;
  bounds.low = low - glm::vec3(reach);
  bounds.high = high + glm::vec3(reach);
  return bounds;
}

int skyOcclusionScale(const LiquidBounds& bounds, const Camera& camera) {
  // Samples 8 pixels apart cost the light benchmark's far block 0.003 of its water's error (12.7 detail radii
  // apart there; 4 pixels are 6.4); on its near frames 8 pixels are 2.4 to 3 radii and moved no error by
  // more than 0.0013.
  constexpr float kSkyOcclusionSpacingInDetailRadii = 6.0f;
  constexpr int kFinest = 4, kCoarsest = 8;
  const float pixel =
      camera.pixelSizeAt(std::max(glm::distance(camera.position(), bounds.centre), camera.nearClip));
  const float pixels = kSkyOcclusionSpacingInDetailRadii * bounds.detailRadius / pixel;
  if (!(pixels >= float(kFinest))) return kFinest;  // also no liquid, or a NaN
  return std::min(int(pixels), kCoarsest);
}

int lightViewSize(const LiquidBounds& bounds, const Camera& camera, const LightParameters& parameters) {
  const int largest = parameters.shadow_map_size;
  if (!(parameters.texels_per_radius > 0.0f) || !(bounds.radius > 0.0f)) return largest;
  const float nearest =
      std::max(glm::distance(camera.position(), bounds.centre) - bounds.radius, camera.nearClip);
  const float pixel = camera.pixelSizeAt(nearest);
  // A view frames the bounding sphere with a 2 % margin (framingCamera). The particles' radius bounds the
  // detail a body of many particles has (its bumps are smoothed away), Mantaflow's kernel radius that of its
  // surface; a body of a few large ones curves at its own size, which a view resolves in kDetailTexels.
  constexpr float kDetailTexels = 128.0f;
  const float side = 2.04f * bounds.radius;
  const float detail = std::min(bounds.detailRadius / parameters.texels_per_radius, side / kDetailTexels);
  const float wanted = std::ceil(side / std::max(detail, pixel));
  constexpr int kSmallest = 32;
  if (!(wanted < float(largest))) return largest;
  return std::max(int(wanted), std::min(kSmallest, largest));
}

std::optional<LightView> lightViewOf(const Light& light, const LiquidBounds& bounds, int size,
                                     std::string* whyNot) {
  LightView view;
  view.light = light;
  if (light.type == Light::Type::Sun) {
    view.camera =
        framingCamera(bounds.centre - light.direction * (kSunDistanceInRadii * bounds.radius), bounds, size);
    view.texelSize = texelSizeAt(view.camera, bounds);
    return view;
  }
  const glm::vec3 toLiquid = bounds.centre - light.position;
  const float distance = glm::length(toLiquid);
  if (distance < 1.05f * bounds.radius) {
    *whyNot = "the light is inside the liquid's bounds";
    return std::nullopt;
  }
  if (light.type == Light::Type::Spot) {
    // The cone misses the bounding sphere when the angle to its centre exceeds the cone's half angle plus the
    // sphere's angular radius.
    const float angleToCentre =
        std::acos(std::clamp(glm::dot(toLiquid / distance, light.direction), -1.0f, 1.0f));
    if (angleToCentre > glm::radians(0.5f * light.spotAngleDegrees) + std::asin(bounds.radius / distance)) {
      *whyNot = "the spot's cone misses the liquid";
      return std::nullopt;
    }
  }
  view.camera = framingCamera(light.position, bounds, size);
  view.texelSize = texelSizeAt(view.camera, bounds);
  return view;
}

LightView skyView(const LiquidBounds& bounds, int size) {
  Light overhead;
  overhead.type = Light::Type::Sun;
  overhead.direction = {0.0f, 0.0f, -1.0f};
  overhead.strength = 0.0f;
  std::string unused;
  LightView view = *lightViewOf(overhead, bounds, size, &unused);
  view.sky = true;
  return view;
}

std::size_t causticLights(const LightingPreparation& lighting) {
  std::size_t count = 0;
  for (const LightPreparation& light : lighting.lights)
    count += light.view.light.type != Light::Type::Point;
  return count;
}

LightsSeeing lightsSeeingTheLiquid(const Particles& particles, const std::vector<Light>& lights,
                                   const LiquidParameters& parameters) {
  LightsSeeing seeing;
  if (lights.empty()) return seeing;
  const LiquidBounds bounds = liquidBounds(particles, parameters);
  if (bounds.radius == 0.0f) return seeing;
  std::string whyNot;
  for (const Light& light : lights) {
    // A view's side does not decide whether there is one.
    if (!lightViewOf(light, bounds, 1, &whyNot)) continue;
    ++seeing.lights;
    seeing.causticLights += light.type != Light::Type::Point;
  }
  return seeing;
}

LightingPreparation prepareLighting(const Particles& particles, const Camera& camera,
                                    const std::vector<Light>& lights, bool worldLightsAlone,
                                    const Parameters& parameters, FrameLiquidCache* frameCache,
                                    OcclusionWorkspace* occlusion) {
  const auto start = std::chrono::steady_clock::now();
  LightingPreparation preparation;
  if (lights.empty() && !worldLightsAlone) return preparation;
  const LiquidBounds bounds = liquidBounds(particles, parameters.liquid);
  preparation.bounds = bounds;
  if (bounds.radius == 0.0f) {
    preparation.skipped.push_back("no liquid particles");
    return preparation;
  }
  // A light sees one body: splashes and aggregates are drawn into the same layers, each shaped as the
  // camera's preparation shapes it.
  // `depthRangeOnly`: the view is drawn as its nearest entry and farthest exit alone, blended (the sky's:
  // EllipsoidImpostorPass::runDepthRange), not as depth-tested layers with normals.
  const auto prepareFor = [&](const LightView& view, bool depthRangeOnly) {
    LightPreparation light{view, prepareLiquid(particles, view.camera, parameters.liquid, frameCache)};
    std::vector<EllipsoidInstance>& body = light.liquid.aggregates;
    body.insert(body.end(), light.liquid.splashes.begin(), light.liquid.splashes.end());
    light.liquid.splashes.clear();
    // The light's layers are the body's nearest entry and farthest exit too, unclipped by the domain. Each
    // view is thinned to the particles nearest and farthest in each column (light.column_particles):
    // - A body few particles deep (a Mantaflow sheet, a spray) hides little from the exact occlusion test,
    //   which costs more than it saves there (the dam break's sun: 4,070 of 56,031 hidden from both layers
    //   for 28 ms of CPU a view; sessions 29 and 39). Thinned by texel columns, the examples' suns and skies
    //   leave out 77 % and their layers take 13 to 22 ms instead of 84 to 105, the error against the user's
    //   render unchanged (docs/liquid.md).
    // - A deep body's lamp views are thinned by columns narrower than its particles' spacing (columnSideFor),
    //   each of which holds about one particle of each layer: the light benchmark's views took 2 to 14 ms of
    //   CPU a frame instead of 12 to 36 with the exact test, their layers' GPU time within -3 to +9 ms
    //   (docs/frame-cost.md, session 58).
    // - The sky's view is drawn as each texel's nearest entry and farthest exit, which a texel column's end
    //   particles hold however deep the body: thinned, the thick bodies' sky layers took 2-3 ms instead of
    //   5-8, their images bit-identical, for under a millisecond of CPU (docs/frame-cost.md, session 44).
    // light.column_particles 0 draws every particle of a view of a body few particles deep and leaves out of
    // a deeper one's only what the exact tests find hidden.
    if (parameters.light.column_particles > 0) {
      const int columnSide = depthRangeOnly ? 1 : columnSideFor(light.liquid.particleSpacing, view.texelSize);
      light.columnThinned = keepColumnEnds(light.liquid.aggregates, light.liquid.aggregateLayers, view.camera,
                                           parameters.light.column_particles, columnSide);
      light.leftOut = light.columnThinned;
    } else if (parameters.liquid.drop_hidden_interior && manyDeepAggregates(light.liquid)) {
      if (depthRangeOnly) {
        // Blending the range costs llvmpipe a few texels an ellipsoid, far less than the occlusion test's CPU
        // time: the thick bodies' sky views took 1 to 8 ms less a frame without it (docs/frame-cost.md,
        // session 43). What lies inside the others is still left out, bit-identically.
        const HiddenInteriorResult hidden = dropHiddenInterior(light.liquid.aggregates, view.camera, nullptr,
                                                               nullptr, light.liquid.particleSpacing);
        light.liquid.aggregateLayers = hidden.split;
        light.leftOut = hidden.dropped;
      } else {
        const HiddenInteriorResult hidden =
            dropHiddenAggregates(light.liquid, view.camera, nullptr, nullptr, occlusion);
        light.leftOut = hidden.dropped + hidden.occluded.dropped;
      }
    }
    return light;
  };
  const int size = lightViewSize(bounds, camera, parameters.light);
  preparation.viewSize = size;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    std::string whyNot;
    std::optional<LightView> view = lightViewOf(lights[i], bounds, size, &whyNot);
    if (!view) {
      preparation.skipped.push_back("lights[" + std::to_string(i) + "]: " + whyNot);
      continue;
    }
    preparation.lights.push_back(prepareFor(*view, false));
  }
  preparation.sky = prepareFor(skyView(bounds, skyViewSide(bounds, camera, parameters.light)), true);
  preparation.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return preparation;
}

const LightingPreparation& LightingAcrossFrames::forFrame(const Particles& particles, const Camera& camera,
                                                          const std::vector<Light>& lights,
                                                          bool worldLightsAlone, const Parameters& parameters,
                                                          FrameLiquidCache* frameCache, bool sameParticles) {
  const auto start = std::chrono::steady_clock::now();
  // The same particles and liquid parameters frame the views alike (the same bounds); the camera only sizes
  // them.
  kept_ = previous_ && sameParticles && lights == lights_ && worldLightsAlone == worldLightsAlone_ &&
          parameters.liquid == liquidParameters_ && parameters.light == lightParameters_ && previous_->sky &&
          lightViewSize(previous_->bounds, camera, parameters.light) == previous_->viewSize &&
          skyViewSide(previous_->bounds, camera, parameters.light) == previous_->sky->view.camera.width;
  if (kept_) {
    previous_->milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return *previous_;
  }
  previous_ =
      prepareLighting(particles, camera, lights, worldLightsAlone, parameters, frameCache, &occlusion_);
  lights_ = lights;
  worldLightsAlone_ = worldLightsAlone;
  liquidParameters_ = parameters.liquid;
  lightParameters_ = parameters.light;
  return *previous_;
}

}  // namespace spindrift
