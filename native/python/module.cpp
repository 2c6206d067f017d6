// The `_spindrift` extension module: the parameter table and the Renderer type (RendererObject.cpp). Built
// against Python's stable ABI (Py_LIMITED_API 3.11), so one binary loads in every Python from 3.11 on.

#include <Python.h>

#include <string>

#include "PythonErrors.h"
#include "PythonValues.h"
#include "RendererObject.h"
#include "spindrift/Parameters.h"

namespace spindrift::python {
namespace {

// parameters.def's type names as the contract spells them.
const char* typeName(const std::string& type) {
  if (type == "Float") return "float";
  if (type == "Int") return "int";
  if (type == "Bool") return "bool";
  if (type == "Color") return "color";
  if (type == "Vec3") return "vec3";
  return "choice";
}

PyObject* parameterTable(PyObject*, PyObject*) {
  try {
    Reference rows(check(PyList_New(0)));
    for (const ParameterInfo& info : spindrift::parameterTable()) {
      const std::size_t dot = info.key.find('.');
      Reference choices(check(PyList_New(0)));
      for (const std::string& choice : info.choices)
        appendToList(choices.get(), Reference(check(toPython(choice))));
      Reference row(check(PyDict_New()));
      setItem(row.get(), "group", Reference(check(toPython(info.key.substr(0, dot)))));
      setItem(row.get(), "name", Reference(check(toPython(info.key.substr(dot + 1)))));
      setItem(row.get(), "type", Reference(check(toPython(std::string(typeName(info.type))))));
      setItem(row.get(), "default", Reference(check(toPython(info.defaultValue, /*arraysAsTuples=*/true))));
      setItem(row.get(), "min", Reference(check(PyFloat_FromDouble(info.minimum))));
      setItem(row.get(), "max", Reference(check(PyFloat_FromDouble(info.maximum))));
      setItem(row.get(), "choices", std::move(choices));
      setItem(row.get(), "doc", Reference(check(toPython(info.doc))));
      appendToList(rows.get(), std::move(row));
    }
    return rows.release();
  } catch (...) {
    return raiseCurrentException();
  }
}

PyMethodDef moduleMethods[] = {{"parameter_table", parameterTable, METH_NOARGS,
                                "parameter_table() -> list[dict]: one dict per row of parameters.def (group, "
                                "name, type, default, min, max, "
                                "choices, doc)."},
                               {nullptr, nullptr, 0, nullptr}};

PyModuleDef moduleDefinition = {PyModuleDef_HEAD_INIT,
                                "_spindrift",
                                "Spindrift's screen-space liquid and foam renderer (native module).",
                                -1,
                                moduleMethods,
                                nullptr,
                                nullptr,
                                nullptr,
                                nullptr};

}  // namespace
}  // namespace spindrift::python

PyMODINIT_FUNC PyInit__spindrift() {
  using namespace spindrift::python;
  Reference module(PyModule_Create(&moduleDefinition));
  if (!module.get()) return nullptr;
  if (PyModule_AddStringConstant(module.get(), "__version__", SPINDRIFT_VERSION) != 0) return nullptr;
  if (!errorType()) {
    PyObject* error = PyErr_NewExceptionWithDoc(
        "_spindrift.Error", "A failure of the native renderer; the message is Spindrift's one-line error.",
        PyExc_RuntimeError, nullptr);
    if (!error) return nullptr;
    setErrorType(error);
  }
  Py_INCREF(errorType());
  if (PyModule_AddObject(module.get(), "Error", errorType()) != 0) {
    Py_DECREF(errorType());
    return nullptr;
  }
  if (!addRendererType(module.get())) return nullptr;
  return module.release();
}
