#pragma once

#include <Python.h>

namespace spindrift::python {

/// Adds the `Renderer` type to the module; false with a Python exception set on failure.
bool addRendererType(PyObject* module);

}  // namespace spindrift::python
