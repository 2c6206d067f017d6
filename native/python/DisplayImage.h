#pragma once

#include <vector>

#include "spindrift/RenderResult.h"

namespace spindrift::python {

/// What the Blender viewport draws: the "foam" layer over the "liquid" layer (both premultiplied RGBA), as
/// premultiplied display sRGB (the viewport's overlay shows values as they are) in 0..1, RGBA float32, rows
/// bottom first as a GL texture wants them. Non-finite values become 0. Throws Error when either layer is
/// missing or not RGBA. Made natively so that no Python runs beside Blender's main thread (docs/blender.md).
std::vector<float> displayImage(const RenderResult& result);

}  // namespace spindrift::python
