#include "ArrayArgument.h"

namespace spindrift::python {
namespace {

// The kind ('f', 'i', 'u', or 0 for anything else) of a struct-module format such as "f", "<i4" or "=B".
char formatKind(const char* format) {
  if (!format) return 'u';  // No format means unsigned bytes.
  while (*format == '@' || *format == '=' || *format == '<')
    ++format;                                            // Native order on little-endian hosts.
  if (format[0] == '\0' || format[1] != '\0') return 0;  // '>' or '!', or a structured type.
  switch (*format) {
    case 'e':
    case 'f':
    case 'd':
      return 'f';
    case 'b':
    case 'h':
    case 'i':
    case 'l':
    case 'q':
    case 'n':
      return 'i';
    case 'B':
    case 'H':
    case 'I':
    case 'L':
    case 'Q':
    case 'N':
      return 'u';
    default:
      return 0;
  }
}

// numpy's name of what was given, for the message.
std::string givenTypeName(const Py_buffer& view) {
  const char kind = formatKind(view.format);
  const std::string bits = std::to_string(view.itemsize * 8);
  if (kind == 'f') return "float" + bits;
  if (kind == 'i') return "int" + bits;
  if (kind == 'u') return "uint" + bits;
  return std::string("format '") + (view.format ? view.format : "") + "'";
}

std::string acceptedNames(const std::vector<ElementType>& accepted) {
  std::string names;
  for (std::size_t i = 0; i < accepted.size(); ++i)
    names += (i == 0 ? "" : i + 1 == accepted.size() ? " or " : ", ") + std::string(accepted[i].name);
  return names;
}

}  // namespace

std::string shapeText(const std::vector<Py_ssize_t>& shape) {
  std::string text = "(";
  for (std::size_t i = 0; i < shape.size(); ++i)
    text += (i ? ", " : "") + (shape[i] == kAnyLength ? std::string("N") : std::to_string(shape[i]));
  return text + (shape.size() == 1 ? ",)" : ")");
}

ArrayArgument::ArrayArgument(PyObject* object, std::string name, const std::vector<ElementType>& accepted,
                             const std::vector<Py_ssize_t>& shape, Access access)
    : name_(std::move(name)) {
  const std::string expected =
      "a C-contiguous " + acceptedNames(accepted) + " array of shape " + shapeText(shape);
  if (!PyObject_CheckBuffer(object)) {
    Reference typeName(PyObject_GetAttrString(reinterpret_cast<PyObject*>(Py_TYPE(object)), "__name__"));
    Py_ssize_t size = 0;
    const char* text = typeName.get() ? PyUnicode_AsUTF8AndSize(typeName.get(), &size) : nullptr;
    PyErr_Clear();
    throw ArgumentError(PyExc_TypeError,
                        name_ + ": expected " + expected + ", got " + (text ? text : "an object"));
  }
  Py_buffer& view = buffer_.view;
  const bool writable = access == Access::Write;
  if (PyObject_GetBuffer(object, &view, writable ? PyBUF_RECORDS : PyBUF_RECORDS_RO) != 0) {
    PyErr_Clear();  // e.g. a buffer without strides, or a read-only one: report it as the argument's fault.
    throw ArgumentError(PyExc_ValueError, name_ + ": expected " + expected + ", and its buffer cannot be " +
                                              (writable ? "written" : "read"));
  }
  buffer_.held = true;
  bool typeAccepted = false;
  for (const ElementType& type : accepted) {
    if (formatKind(view.format) == type.kind && view.itemsize == type.size) {
      type_ = type;
      typeAccepted = true;
    }
  }
  if (!typeAccepted)
    throw ArgumentError(PyExc_ValueError, name_ + ": expected " + acceptedNames(accepted) + ", got " +
                                              givenTypeName(view) + " (convert with .astype(numpy." +
                                              accepted[0].name + "); nothing is converted silently)");
  std::vector<Py_ssize_t> given(view.shape, view.shape + view.ndim);
  bool shapeMatches = given.size() == shape.size();
  for (std::size_t axis = 0; shapeMatches && axis < shape.size(); ++axis)
    shapeMatches = shape[axis] == kAnyLength || shape[axis] == given[axis];
  if (!shapeMatches) {
    if (shape.size() == 1 && given.size() == 1)
      throw ArgumentError(PyExc_ValueError, name_ + ": expected " + std::to_string(shape[0]) + " " +
                                                type_.name + " values, got " + std::to_string(given[0]));
    throw ArgumentError(PyExc_ValueError,
                        name_ + ": expected shape " + shapeText(shape) + ", got " + shapeText(given));
  }
  if (!PyBuffer_IsContiguous(&view, 'C'))
    throw ArgumentError(PyExc_ValueError,
                        name_ + ": the array is not C-contiguous (pass numpy.ascontiguousarray(...))");
}

}  // namespace spindrift::python
