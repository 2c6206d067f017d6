#pragma once

#include "gl/GlObjects.h"
#include "passes/DepthPingPong.h"

namespace spindrift {

/// The widest 1D kernel the separable depth filters use, in pixels from the centre: a particle close to the
/// camera would otherwise ask for hundreds of taps per pixel.
constexpr int kMaximumFilterRadiusInPixels = 32;

/// Runs a separable depth filter `iterations` times, each an x pass and a y pass of `program` (whose
/// `direction` uniform picks the axis), and returns the last result (`eyeDepth` itself with no iterations).
/// The program must be current, with its other uniforms set.
const Texture2D& runSeparableFilter(GLuint program, const Texture2D& eyeDepth, int iterations,
                                    DepthPingPong& targets);

}  // namespace spindrift
