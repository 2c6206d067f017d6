#include "PythonErrors.h"

#include <new>

#include "spindrift/Error.h"

namespace spindrift::python {
namespace {
PyObject* moduleErrorType = nullptr;
}

PyObject* errorType() {
  return moduleErrorType;
}
void setErrorType(PyObject* type) {
  moduleErrorType = type;
}

PyObject* raiseCurrentException() {
  try {
    throw;
  } catch (const PythonErrorSet&) {
    // The Python C API has set the exception already.
  } catch (const ArgumentError& error) {
    PyErr_SetString(error.type(), error.what());
  } catch (const spindrift::Error& error) {
    PyErr_SetString(moduleErrorType, error.what());
  } catch (const std::bad_alloc&) {
    PyErr_NoMemory();
  } catch (const std::exception& error) {
    PyErr_SetString(moduleErrorType, error.what());
  } catch (...) {
    PyErr_SetString(moduleErrorType, "unknown native failure");
  }
  return nullptr;
}

}  // namespace spindrift::python
