#include "FrameArguments.h"

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <optional>
#include <string>

#include "ArrayArgument.h"

namespace spindrift::python {
namespace {

// The dictionary argument itself, and its keys: a misspelt key must not pass silently.
void requireDictionary(PyObject* dictionary, const char* name, std::initializer_list<const char*> allowed) {
  if (!PyDict_Check(dictionary))
    throw ArgumentError(PyExc_TypeError, std::string(name) + ": expected a dict");
  PyObject* key = nullptr;
  PyObject* value = nullptr;
  Py_ssize_t position = 0;
  while (PyDict_Next(dictionary, &position, &key, &value)) {
    Py_ssize_t size = 0;
    const char* text = PyUnicode_Check(key) ? PyUnicode_AsUTF8AndSize(key, &size) : nullptr;
    if (!text) {
      PyErr_Clear();
      throw ArgumentError(PyExc_TypeError, std::string(name) + ": keys must be strings");
    }
    bool known = false;
    for (const char* name : allowed)
      known = known || std::strcmp(name, text) == 0;
    if (!known) {
      std::string names;
      for (const char* name : allowed)
        names += (names.empty() ? "" : ", ") + std::string(name);
      throw ArgumentError(PyExc_ValueError,
                          std::string(name) + ": unknown key '" + text + "' (expected " + names + ")");
    }
  }
}

// The value of a key that must be present, or null for an optional one (a None value counts as absent).
PyObject* item(PyObject* dictionary, const char* name, const char* key, bool required) {
  PyObject* value = PyDict_GetItemString(dictionary, key);
  if (value == Py_None) value = nullptr;
  if (!value && required)
    throw ArgumentError(PyExc_ValueError, std::string(name) + ": missing '" + key + "'");
  return value;
}

std::string keyName(const char* name, const char* key) {
  return std::string(name) + "[\"" + key + "\"]";
}

template <typename Vector>
void copyInto(Vector& target, const ArrayArgument& array) {
  target.resize(std::size_t(array.count()) / (sizeof(typename Vector::value_type) / array.type().size));
  if (array.count() > 0)
    std::memcpy(target.data(), array.data(), std::size_t(array.count()) * array.type().size);
}

}  // namespace

Particles readParticles(PyObject* dictionary) {
  const char* name = "particles";
  requireDictionary(dictionary, name, {"positions", "radii", "kinds", "life", "velocities"});
  const ArrayArgument positions(item(dictionary, name, "positions", true), keyName(name, "positions"),
                                {kFloat32}, {kAnyLength, 3});
  const Py_ssize_t count = positions.count() / 3;
  const ArrayArgument radii(item(dictionary, name, "radii", true), keyName(name, "radii"), {kFloat32},
                            {count});
  const ArrayArgument kinds(item(dictionary, name, "kinds", true), keyName(name, "kinds"), {kUInt8}, {count});
  Particles particles;
  copyInto(particles.positions, positions);
  copyInto(particles.radii, radii);
  particles.kinds.resize(std::size_t(count));
  const auto* kindValues = static_cast<const std::uint8_t*>(kinds.data());
  for (Py_ssize_t i = 0; i < count; ++i) {
    const std::uint8_t kind = kindValues[i];
    if (kind != 0 && kind != 2 && kind != 4 && kind != 8)
      throw ArgumentError(PyExc_ValueError, keyName(name, "kinds") + ": value " + std::to_string(kind) +
                                                " at index " + std::to_string(i) +
                                                " is not 0 (liquid), 2 (spray), 4 (bubble) or 8 (foam)");
    particles.kinds[std::size_t(i)] = ParticleKind(kind);
  }
  if (PyObject* life = item(dictionary, name, "life", false))
    copyInto(particles.life, ArrayArgument(life, keyName(name, "life"), {kFloat32}, {count}));
  if (PyObject* velocities = item(dictionary, name, "velocities", false))
    copyInto(particles.velocities,
             ArrayArgument(velocities, keyName(name, "velocities"), {kFloat32}, {count, 3}));
  return particles;
}

TriangleMesh readTriangleMesh(PyObject* dictionary, const char* name) {
  requireDictionary(dictionary, name, {"vertices", "triangles"});
  const ArrayArgument vertices(item(dictionary, name, "vertices", true), keyName(name, "vertices"),
                               {kFloat32}, {kAnyLength, 3});
  const ArrayArgument triangles(item(dictionary, name, "triangles", true), keyName(name, "triangles"),
                                {kInt32, kUInt32}, {kAnyLength, 3});
  TriangleMesh mesh;
  copyInto(mesh.vertices, vertices);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const glm::vec3& v = mesh.vertices[i];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      throw ArgumentError(PyExc_ValueError,
                          keyName(name, "vertices") + ": vertex " + std::to_string(i) + " is not finite");
  }
  const std::size_t vertexCount = mesh.vertices.size();
  const std::size_t indexCount = std::size_t(triangles.count());
  mesh.triangles.resize(indexCount / 3);
  const bool isSigned = triangles.type().kind == 'i';
  const auto* indices = static_cast<const std::uint32_t*>(triangles.data());
  for (std::size_t i = 0; i < indexCount; ++i) {
    const std::uint32_t index = indices[i];
    if ((isSigned && std::int32_t(index) < 0) || index >= vertexCount)
      throw ArgumentError(PyExc_ValueError,
                          keyName(name, "triangles") + ": triangle " + std::to_string(i / 3) +
                              " names vertex " +
                              (isSigned ? std::to_string(std::int32_t(index)) : std::to_string(index)) +
                              ", outside the " + std::to_string(vertexCount) + " vertices");
    mesh.triangles[i / 3][int(i % 3)] = index;
  }
  return mesh;
}

void readBackground(PyObject* dictionary, const Camera& camera, FrameInputs& inputs) {
  const char* name = "background";
  requireDictionary(dictionary, name, {"color", "depth"});
  auto image = [&](const ArrayArgument& array, int channels) {
    FloatImage result;
    result.width = camera.width;
    result.height = camera.height;
    result.channels = channels;
    copyInto(result.pixels, array);
    return result;
  };
  if (PyObject* color = item(dictionary, name, "color", false))
    inputs.backgroundColor =
        image(ArrayArgument(color, keyName(name, "color"), {kFloat32}, {camera.height, camera.width, 4}), 4);
  if (PyObject* depth = item(dictionary, name, "depth", false))
    inputs.backgroundDepth =
        image(ArrayArgument(depth, keyName(name, "depth"), {kFloat32}, {camera.height, camera.width}), 1);
}

}  // namespace spindrift::python
