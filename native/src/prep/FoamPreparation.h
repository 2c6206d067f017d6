#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "spindrift/Camera.h"
#include "spindrift/Parameters.h"
#include "spindrift/Particles.h"

namespace spindrift {

/// The foam paper's three kinds of diffuse particle, as the foam shaders number them.
enum class FoamType : int { Spray = 0, Surface = 1, Bubble = 2 };

/// One foam particle as the sprite passes draw it. Laid out for a std430 shader storage buffer (32 bytes).
struct FoamInstance {
  glm::vec4 centreAndRadius;  ///< World centre; w: the drawn radius (bubble scale and irregularity applied).
  glm::vec4 typeAndAge;       ///< x: FoamType; y: normalised age l in [0, 1] (0 when the life is unknown).
};
static_assert(sizeof(FoamInstance) == 32, "FoamInstance must match the shaders' std430 layout");

/// The foam particles of one frame that the view can see, ready to draw.
struct FoamPreparation {
  std::vector<FoamInstance> instances;
  std::size_t spray = 0;  ///< In view, by type.
  std::size_t surface = 0;
  std::size_t bubble = 0;
  std::size_t culled = 0;  ///< Foam particles outside the view frustum.
  /// In view (and counted by type above) but left out: their sprites hold no pixel's centre
  /// (foam.cull_sub_pixel).
  std::size_t subPixel = 0;
};

/// The radius the foam paper draws particle `index` (its place among the frame's foam particles) with:
/// r / ((index mod k) + 1), halved (bubble_radius_scale) for bubbles.
float foamDrawnRadius(float radius, ParticleKind kind, std::size_t index, const FoamParameters& parameters);

/// The normalised age l of a particle with `lifeFrames` frames of life left: 1 - life / lifetime_frames,
/// clamped to [0, 1]; 0 (no fade) when the life is unknown (0) or lifetime_frames is 0.
float foamNormalisedAge(float lifeFrames, const FoamParameters& parameters);

/// Whether a sprite, the ellipse of semi-axes `radiusPixels` (x, y) about `windowCentre` (window coordinates,
/// pixel centres at +0.5) that a disc of its drawn radius projects to, holds the centre of any pixel: where
/// the sprite passes rasterise a fragment. Conservative: an ellipse grown by 1 % and 0.01 px that holds one
/// counts, so the shaders' own rounding never makes a fragment where this found none.
bool foamSpriteHoldsAPixelCentre(const glm::vec2& windowCentre, const glm::vec2& radiusPixels);

/// Culls the Spray, Bubble and Foam particles to the view and packs them (foam paper 2.1).
FoamPreparation prepareFoam(const Particles& particles, const Camera& camera,
                            const FoamParameters& parameters);

}  // namespace spindrift
