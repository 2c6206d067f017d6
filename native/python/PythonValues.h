#pragma once

// Conversions from the library's values (JSON, strings) to Python objects. Each returns a new reference or
// null with a Python exception set.

#include <Python.h>

#include <string>

#include <nlohmann/json.hpp>

#include "PythonErrors.h"

namespace spindrift::python {

PyObject* toPython(const std::string& text);
/// Objects become dicts, numbers int or float, arrays lists (tuples when `arraysAsTuples`).
PyObject* toPython(const nlohmann::json& value, bool arraysAsTuples = false);

/// dict[key] = value; throws PythonErrorSet when Python fails.
void setItem(PyObject* dictionary, const char* key, Reference value);
void appendToList(PyObject* list, Reference value);

}  // namespace spindrift::python
