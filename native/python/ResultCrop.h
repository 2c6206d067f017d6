#pragma once

#include "spindrift/RenderResult.h"

namespace spindrift::python {

/// A window of the image: `x` columns from the left, `y` rows from the top, `width` x `height` pixels.
struct CropWindow {
  int x = 0, y = 0, width = 0, height = 0;
};

/// Cuts every layer of `result` to `window` (which must lie inside the image). An off-axis camera (a Blender
/// camera's lens shift) is rendered as the larger symmetric camera that contains its view and cut here, so
/// refraction_uv's u, v (0..1 over the whole image, origin bottom left) are re-expressed over the window, and
/// clamped to its outermost pixel centres: the compositor's Map UV only has the window's render to read, and
/// a ray refracted outside it reads the nearest edge pixel.
void cropResult(RenderResult& result, const CropWindow& window);

}  // namespace spindrift::python
