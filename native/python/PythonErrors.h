#pragma once

// How the module reports failures: argument problems as ValueError/TypeError, everything the native library
// throws as _spindrift.Error. No exception ever crosses into Python's C code (nothing may abort Blender).

#include <Python.h>

#include <stdexcept>
#include <string>

namespace spindrift::python {

/// A bad argument: raised in Python as `type` (PyExc_ValueError or PyExc_TypeError) with the message.
class ArgumentError : public std::runtime_error {
 public:
  ArgumentError(PyObject* type, const std::string& message) : std::runtime_error(message), type_(type) {}
  PyObject* type() const { return type_; }

 private:
  PyObject* type_;
};

/// `_spindrift.Error`, made when the module is initialised.
PyObject* errorType();
void setErrorType(PyObject* type);

/// Sets the Python exception for the exception being handled (call inside `catch (...)`) and returns nullptr.
/// An exception already set by the Python C API (PythonErrorSet) is left as it is.
PyObject* raiseCurrentException();

/// Thrown after a Python C API call has failed and set its own exception.
struct PythonErrorSet {};

/// Throws PythonErrorSet when `object` is null (a failed Python C API call); returns it otherwise.
inline PyObject* check(PyObject* object) {
  if (!object) throw PythonErrorSet{};
  return object;
}

/// An owned reference, released when it goes.
class Reference {
 public:
  Reference() = default;
  explicit Reference(PyObject* object) : object_(object) {}
  ~Reference() { Py_XDECREF(object_); }
  Reference(Reference&& other) noexcept : object_(other.release()) {}
  /// Needs the GIL (it releases what it held).
  Reference& operator=(Reference&& other) noexcept {
    if (this != &other) {
      Py_XDECREF(object_);
      object_ = other.release();
    }
    return *this;
  }
  Reference(const Reference&) = delete;
  Reference& operator=(const Reference&) = delete;
  PyObject* get() const { return object_; }
  PyObject* release() {
    PyObject* object = object_;
    object_ = nullptr;
    return object;
  }

 private:
  PyObject* object_ = nullptr;
};

}  // namespace spindrift::python
