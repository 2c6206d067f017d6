#include "prep/FoamPreparation.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "prep/ViewFrustum.h"

namespace spindrift {

float foamDrawnRadius(float radius, ParticleKind kind, std::size_t index, const FoamParameters& parameters) {
  // The particle's index is the only identity a cache gives it; the paper uses its id the same way.
  const float irregularity = float(index % std::size_t(parameters.radius_variation) + 1);
  const float kindScale = kind == ParticleKind::Bubble ? parameters.bubble_radius_scale : 1.0f;
  return radius * kindScale / irregularity;
}

float foamNormalisedAge(float lifeFrames, const FoamParameters& parameters) {
  if (!(lifeFrames > 0.0f) || !(parameters.lifetime_frames > 0.0f)) return 0.0f;
  return std::clamp(1.0f - lifeFrames / parameters.lifetime_frames, 0.0f, 1.0f);
}

bool foamSpriteHoldsAPixelCentre(const glm::vec2& windowCentre, const glm::vec2& radiusPixels) {
  const glm::vec2 grown = radiusPixels * 1.01f + 0.01f;
  // A pixel or more across along an axis: kept untested (such a sprite nearly always holds a centre). So are
  // NaN sizes and positions, whatever the shaders make of them.
  if (!(grown.x < 1.0f && grown.y < 1.0f) || !std::isfinite(windowCentre.x + windowCentre.y)) return true;
  // Narrower than a pixel along both axes, the ellipse can hold only the four centres around its own: those
  // less than a pixel away along each axis.
  const glm::vec2 first = glm::floor(windowCentre - 0.5f) + 0.5f;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      const glm::vec2 offset = (first + glm::vec2(dx, dy) - windowCentre) / grown;
      if (glm::dot(offset, offset) <= 1.0f) return true;
    }
  return false;
}

FoamPreparation prepareFoam(const Particles& particles, const Camera& camera,
                            const FoamParameters& parameters) {
  const ViewFrustum frustum(camera);
  // A sprite's window position and radius as foam_sprite.vert makes them: clip = clipFromCamera * centre, the
  // disc of radius r at the centre's depth spans r clipFromCamera[0][0] (and [1][1]) in clip x (and y).
  const glm::mat4 clipFromCamera = camera.clipFromCamera();
  const glm::vec2 halfSize = 0.5f * glm::vec2(float(camera.width), float(camera.height));
  const glm::vec2 clipPerUnit(clipFromCamera[0][0], clipFromCamera[1][1]);
  FoamPreparation result;
  std::size_t foamIndex = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const ParticleKind kind = particles.kinds[i];
    if (kind == ParticleKind::Liquid) continue;
    const float radius = foamDrawnRadius(particles.radii[i], kind, foamIndex++, parameters);
    const glm::vec3 cameraCentre = frustum.cameraFromWorld(particles.positions[i]);
    // A sprite cannot cover a sphere that contains the camera, so those are culled with the invisible ones.
    if (!frustum.reachedBySphere(cameraCentre, radius) ||
        glm::dot(cameraCentre, cameraCentre) <= radius * radius) {
      ++result.culled;
      continue;
    }
    const FoamType type = kind == ParticleKind::Spray    ? FoamType::Spray
                          : kind == ParticleKind::Bubble ? FoamType::Bubble
                                                         : FoamType::Surface;
    (type == FoamType::Spray ? result.spray : type == FoamType::Bubble ? result.bubble : result.surface)++;
    // A centre at or behind the near plane: foam_sprite.vert draws it off the screen already.
    if (parameters.cull_sub_pixel && -cameraCentre.z > camera.nearClip) {
      const glm::vec4 clip = clipFromCamera * glm::vec4(cameraCentre, 1.0f);
      const glm::vec2 windowCentre = (glm::vec2(clip) / clip.w + 1.0f) * halfSize;
      if (!foamSpriteHoldsAPixelCentre(windowCentre, radius * clipPerUnit / clip.w * halfSize)) {
        ++result.subPixel;
        continue;
      }
    }
    result.instances.push_back(
        {glm::vec4(particles.positions[i], radius),
         glm::vec4(float(int(type)), foamNormalisedAge(particles.life[i], parameters), 0.0f, 0.0f)});
  }
  return result;
}

}  // namespace spindrift
