#include "PythonValues.h"

namespace spindrift::python {

PyObject* toPython(const std::string& text) {
  return PyUnicode_DecodeUTF8(text.data(), Py_ssize_t(text.size()), "replace");
}

PyObject* toPython(const nlohmann::json& value, bool arraysAsTuples) {
  switch (value.type()) {
    case nlohmann::json::value_t::null:
      Py_INCREF(Py_None);
      return Py_None;
    case nlohmann::json::value_t::boolean:
      return PyBool_FromLong(value.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return PyLong_FromLongLong(value.get<long long>());
    case nlohmann::json::value_t::number_unsigned:
      return PyLong_FromUnsignedLongLong(value.get<unsigned long long>());
    case nlohmann::json::value_t::number_float:
      return PyFloat_FromDouble(value.get<double>());
    case nlohmann::json::value_t::string:
      return toPython(value.get<std::string>());
    case nlohmann::json::value_t::array: {
      Reference items(PyList_New(0));
      if (!items.get()) return nullptr;
      for (const nlohmann::json& element : value) {
        Reference converted(toPython(element, arraysAsTuples));
        if (!converted.get() || PyList_Append(items.get(), converted.get()) != 0) return nullptr;
      }
      return arraysAsTuples ? PyList_AsTuple(items.get()) : items.release();
    }
    case nlohmann::json::value_t::object: {
      Reference dictionary(PyDict_New());
      if (!dictionary.get()) return nullptr;
      for (const auto& [key, element] : value.items()) {
        Reference converted(toPython(element, arraysAsTuples));
        if (!converted.get() || PyDict_SetItemString(dictionary.get(), key.c_str(), converted.get()) != 0)
          return nullptr;
      }
      return dictionary.release();
    }
    default:
      PyErr_SetString(PyExc_TypeError, "a JSON value Python cannot hold");
      return nullptr;
  }
}

void setItem(PyObject* dictionary, const char* key, Reference value) {
  if (PyDict_SetItemString(dictionary, key, value.get()) != 0) throw PythonErrorSet{};
}

void appendToList(PyObject* list, Reference value) {
  if (PyList_Append(list, value.get()) != 0) throw PythonErrorSet{};
}

}  // namespace spindrift::python
