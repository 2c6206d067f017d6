#pragma once

#include <vector>

#include "prep/LiquidPreparation.h"
#include "spindrift/Camera.h"

namespace spindrift {

/// A rectangle of a view's pixels, from the bottom left as glScissor takes it.
struct WindowRectangle {
  int x = 0, y = 0, width = 0, height = 0;
  long long pixels() const { return (long long)width * height; }
};

/// The pixels that can hold any of the ellipsoids as `view` projects them: the projection of their bounding
/// spheres' box in camera space, a pixel wider on each side, within the view. Empty for no ellipsoids; the
/// whole view where that box reaches the near plane or holds a value that is not finite. The normal resolve
/// of the impostor pass shades only these (EllipsoidImpostorPass).
WindowRectangle windowRectangleOfSpheres(const std::vector<EllipsoidInstance>& ellipsoids,
                                         const Camera& view);

}  // namespace spindrift
