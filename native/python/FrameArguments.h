#pragma once

// The keyword arguments of Renderer.render that hand data in memory, read into the library's FrameInputs.
// Needs the GIL; copies every array, so the render itself runs without Python objects.

#include <Python.h>

#include "spindrift/FrameInputs.h"
#include "spindrift/Scene.h"

namespace spindrift::python {

/// {"positions": (N,3) float32, "radii": (N,) float32, "kinds": (N,) uint8, "life": (N,) float32 optional,
///  "velocities": (N,3) float32 optional}. Kinds must be 0, 2, 4 or 8.
Particles readParticles(PyObject* dictionary);

/// {"vertices": (V,3) float32, "triangles": (T,3) int32 or uint32}; `name` prefixes messages.
TriangleMesh readTriangleMesh(PyObject* dictionary, const char* name);

/// {"color": (H,W,4) float32 optional, "depth": (H,W) float32 optional}, H and W the camera's.
void readBackground(PyObject* dictionary, const Camera& camera, FrameInputs& inputs);

}  // namespace spindrift::python
