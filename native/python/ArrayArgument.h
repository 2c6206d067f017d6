#pragma once

// Validation of array arguments taken through the buffer protocol (numpy arrays, memoryviews, ...): one place
// that checks element type, shape and C-contiguity and says what was expected in a ValueError/TypeError, so
// no wrong array ever reaches the native library (OpenImageIO's python bindings do the same in oiio_bufinfo).

#include <Python.h>

#include <cstddef>
#include <string>
#include <vector>

#include "PythonErrors.h"

namespace spindrift::python {

/// An element type the module accepts: numpy's name, the kind of struct format character and the size.
struct ElementType {
  const char* name;  ///< "float32", "uint8", "int32", "uint32"
  char kind;         ///< 'f' floating point, 'i' signed integer, 'u' unsigned integer
  Py_ssize_t size;
};

inline constexpr ElementType kFloat32{"float32", 'f', 4};
inline constexpr ElementType kUInt8{"uint8", 'u', 1};
inline constexpr ElementType kInt32{"int32", 'i', 4};
inline constexpr ElementType kUInt32{"uint32", 'u', 4};

/// Any length along an axis of an expected shape.
inline constexpr Py_ssize_t kAnyLength = -1;

/// A validated, C-contiguous, read-only view of an array argument; the buffer is released when it goes.
/// Every check throws ArgumentError naming the argument, e.g.
/// `particles["radii"]: expected 1200 float32 values, got 1199`.
class ArrayArgument {
 public:
  /// `shape` gives the expected length of every axis (kAnyLength for free ones); `accepted` the element
  /// types.
  /// With Access::Write the buffer must also be writable (an output the module fills).
  enum class Access { Read, Write };
  ArrayArgument(PyObject* object, std::string name, const std::vector<ElementType>& accepted,
                const std::vector<Py_ssize_t>& shape, Access access = Access::Read);
  ArrayArgument(const ArrayArgument&) = delete;
  ArrayArgument& operator=(const ArrayArgument&) = delete;

  const void* data() const { return buffer_.view.buf; }
  /// Only for an Access::Write argument.
  void* writableData() const { return buffer_.view.buf; }
  /// The number of elements (the product of the shape).
  Py_ssize_t count() const { return buffer_.view.len / buffer_.view.itemsize; }
  const ElementType& type() const { return type_; }
  const std::string& name() const { return name_; }

 private:
  // A member, so the buffer is released also when the constructor throws after taking it.
  struct HeldBuffer {
    Py_buffer view{};
    bool held = false;
    ~HeldBuffer() {
      if (held) PyBuffer_Release(&view);
    }
  };
  HeldBuffer buffer_;
  std::string name_;
  ElementType type_{};
};

/// "(N, 3)" or "(1200, 3)": a shape as a message shows it, kAnyLength as N.
std::string shapeText(const std::vector<Py_ssize_t>& shape);

}  // namespace spindrift::python
