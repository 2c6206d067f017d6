#include "FrameRequest.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <set>
#include <utility>

#include "ArrayArgument.h"
#include "DisplayImage.h"
#include "FrameArguments.h"
#include "PythonErrors.h"
#include "PythonValues.h"
#include "Readback.h"

namespace spindrift::python {
namespace {

// The layer names asked for; nothing means every layer (None), an empty list none at all. `argument` names
// the keyword in messages; an unknown layer is a ValueError listing the frame's layers.
std::optional<std::vector<std::string>> readLayerNames(PyObject* layers, const char* argument) {
  std::vector<std::string> names;
  if (layers == Py_None) return std::nullopt;
  if (!PyList_Check(layers) && !PyTuple_Check(layers))
    throw ArgumentError(PyExc_TypeError, std::string(argument) + ": expected a list of layer names");
  Reference items(check(PySequence_List(layers)));
  const std::vector<std::string>& known = LayerSelection::allNames();
  for (Py_ssize_t i = 0; i < PyList_Size(items.get()); ++i) {
    PyObject* name = PyList_GetItem(items.get(), i);
    Py_ssize_t size = 0;
    const char* text = PyUnicode_Check(name) ? PyUnicode_AsUTF8AndSize(name, &size) : nullptr;
    if (!text) {
      PyErr_Clear();
      throw ArgumentError(PyExc_TypeError,
                          std::string(argument) + "[" + std::to_string(i) + "]: expected a str");
    }
    names.emplace_back(text, std::size_t(size));
    if (std::find(known.begin(), known.end(), names.back()) == known.end()) {
      std::string list;
      for (const std::string& layer : known)
        list += (list.empty() ? "" : ", ") + layer;
      throw ArgumentError(PyExc_ValueError, std::string(argument) + ": no layer named '" + names.back() +
                                                "' (the frame has " + list + ")");
    }
  }
  return names;
}

void addName(std::vector<std::string>& names, const std::string& name) {
  if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
}

// The layers the frame must render: those returned, those written and those the display image is made of,
// or every layer when the returned or written set is "all". Passes that feed none of them are not run
// (Renderer::setLayers), which is what makes a frame that only needs the compositor's six layers cheaper
// than a full one.
std::vector<std::string> layersToRender(const FrameRequest& request) {
  const bool writing = request.exrPath.has_value();
  if (!request.layers || (writing && !request.exrLayers)) return {};  // Empty: all.
  std::vector<std::string> names = *request.layers;
  if (writing)
    for (const std::string& name : *request.exrLayers)
      addName(names, name);
  if (request.display) {
    addName(names, "liquid");
    addName(names, "foam");
  }
  return names;
}

// `crop`: None, or (x, y, width, height) in pixels, y from the top, inside the camera's image.
std::optional<CropWindow> readCropWindow(PyObject* crop, const Camera& camera) {
  if (crop == Py_None) return std::nullopt;
  CropWindow window;
  if (!PyTuple_Check(crop) ||
      !PyArg_ParseTuple(crop, "iiii", &window.x, &window.y, &window.width, &window.height)) {
    PyErr_Clear();
    throw ArgumentError(PyExc_TypeError, "crop: expected a tuple (x, y, width, height) of ints");
  }
  if (window.x < 0 || window.y < 0 || window.width < 1 || window.height < 1 ||
      window.x + window.width > camera.width || window.y + window.height > camera.height)
    throw ArgumentError(PyExc_ValueError, "crop: " + std::to_string(window.width) + "x" +
                                              std::to_string(window.height) + " at (" +
                                              std::to_string(window.x) + ", " + std::to_string(window.y) +
                                              ") does not lie inside the " + std::to_string(camera.width) +
                                              "x" + std::to_string(camera.height) + " camera image");
  return window;
}

char* checkBytes(char* bytes) {
  if (!bytes) throw PythonErrorSet{};
  return bytes;
}

// A bytes object of `size` bytes, made (uninitialised) with the GIL; `target` is where to fill it without.
Reference uninitialisedBytes(std::size_t size, char*& target) {
  Reference bytes(check(PyBytes_FromStringAndSize(nullptr, Py_ssize_t(size))));
  target = checkBytes(PyBytes_AsString(bytes.get()));
  return bytes;
}

}  // namespace

FrameRequest readFrameRequest(PyObject* args, PyObject* kwargs) {
  static const char* keywords[] = {"scene_json", "frame",       "base_dir",       "particles",
                                   "occluders",  "liquid_mesh", "background",     "exr_path",
                                   "layers",     "exr_layers",  "exr_half_color", "exr_compression",
                                   "crop",       "display",     "display_into",   nullptr};
  const char* sceneJson = nullptr;
  int frame = 0;
  const char* baseDir = "";
  PyObject *particles = Py_None, *occluders = Py_None, *liquidMesh = Py_None, *background = Py_None;
  const char* exrPath = nullptr;
  PyObject *layers = Py_None, *exrLayers = Py_None, *crop = Py_None;
  int exrHalfColor = 0, display = 0;
  PyObject* displayInto = Py_None;
  const std::string defaultCompression = ExrOptions{}.compression;
  const char* exrCompression = defaultCompression.c_str();
  if (!PyArg_ParseTupleAndKeywords(args, kwargs, "si|$sOOOOzOOpsOpO", const_cast<char**>(keywords),
                                   &sceneJson, &frame, &baseDir, &particles, &occluders, &liquidMesh,
                                   &background, &exrPath, &layers, &exrLayers, &exrHalfColor, &exrCompression,
                                   &crop, &display, &displayInto))
    throw PythonErrorSet{};
  FrameRequest request;
  // Relative paths in the scene are anchored at base_dir; messages name the scene "<base_dir>/scene_json".
  const std::filesystem::path anchor = std::filesystem::path(*baseDir ? baseDir : ".") / "scene_json";
  request.scene = parseScene(sceneJson, anchor);
  request.frame = frame;
  if (particles != Py_None) request.inputs.particles = readParticles(particles);
  if (occluders != Py_None) {
    if (PyList_Check(occluders)) {
      for (Py_ssize_t i = 0; i < PyList_Size(occluders); ++i)
        request.inputs.occluders.push_back(
            readTriangleMesh(PyList_GetItem(occluders, i), ("occluders[" + std::to_string(i) + "]").c_str()));
    } else {
      request.inputs.occluders.push_back(readTriangleMesh(occluders, "occluders"));
    }
  }
  if (liquidMesh != Py_None) request.inputs.liquidMesh = readTriangleMesh(liquidMesh, "liquid_mesh");
  if (background != Py_None) {
    // The in-memory background replaces the scene's background files (an environment and liquid_depth stay).
    request.scene.background.image.clear();
    request.scene.background.depth.clear();
    request.scene.background.depthExplicit = false;
    readBackground(background, request.scene.camera, request.inputs);
  }
  request.layers = readLayerNames(layers, "layers");
  request.exrLayers = readLayerNames(exrLayers, "exr_layers");
  if (exrPath) request.exrPath = std::filesystem::path(exrPath);
  request.exrOptions =
      ExrOptions{exrHalfColor != 0, exrCompression, request.exrLayers.value_or(std::vector<std::string>{})};
  request.crop = readCropWindow(crop, request.scene.camera);
  request.display = display != 0;
  if (displayInto != Py_None) {
    if (!request.display) throw ArgumentError(PyExc_ValueError, "display_into: needs display=True");
    const Camera& camera = request.scene.camera;
    const Py_ssize_t pixels = request.crop ? Py_ssize_t(request.crop->width) * request.crop->height
                                           : Py_ssize_t(camera.width) * camera.height;
    request.displayTarget =
        std::make_unique<ArrayArgument>(displayInto, "display_into", std::vector<ElementType>{kFloat32},
                                        std::vector<Py_ssize_t>{4 * pixels}, ArrayArgument::Access::Write);
    Py_INCREF(displayInto);
    request.displayObject = Reference(displayInto);
  }
  return request;
}

FrameOutcome renderRequest(Renderer& renderer, const FrameRequest& request) {
  FrameOutcome outcome;
  // Every call sets its own selection: the Renderer keeps it, and calls may ask for different layers.
  renderer.setLayers(layersToRender(request));
  outcome.result = renderer.renderFrame(request.scene, request.frame, request.inputs);
  if (request.crop) cropResult(outcome.result, *request.crop);
  if (request.display) {
    outcome.display = displayImage(outcome.result);
    if (request.displayTarget) {
      // Written here, on the rendering thread, so that faulting in the caller's fresh pages costs its thread
      // nothing (15-30 ms per 640x400 frame on this project's virtual machine; docs/blender.md).
      std::memcpy(request.displayTarget->writableData(), outcome.display.data(),
                  outcome.display.size() * sizeof(float));
      outcome.display.clear();
    }
  }
  if (!request.exrPath) return outcome;
  const auto writeStart = std::chrono::steady_clock::now();
  writeExr(outcome.result, *request.exrPath, request.exrOptions);
  outcome.exrWriteMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - writeStart).count();
  return outcome;
}

PyObject* outcomeToPython(const FrameOutcome& outcome, const FrameRequest& request) {
  const RenderResult& result = outcome.result;
  std::set<std::string> available;
  for (const ImageLayer& layer : result.layers)
    available.insert(layer.name);
  for (const std::string& name : request.layers.value_or(std::vector<std::string>{})) {
    if (!available.count(name)) {
      std::string names;
      for (const std::string& known : available)
        names += (names.empty() ? "" : ", ") + known;
      throw ArgumentError(PyExc_ValueError,
                          "layers: no layer named '" + name + "' (the frame has " + names + ")");
    }
  }
  Reference layers(check(PyDict_New()));
  // The bytes objects are made (uninitialised) with the GIL, and filled without it: copying a full frame's
  // layers takes long enough on a busy machine to stall Blender's UI thread otherwise.
  std::vector<std::pair<char*, const std::vector<float>*>> copies;
  for (const ImageLayer& layer : result.layers) {
    const auto& wanted = request.layers;
    if (wanted && std::find(wanted->begin(), wanted->end(), layer.name) == wanted->end()) continue;
    Reference channels(check(PyTuple_New(Py_ssize_t(layer.channels.size()))));
    for (std::size_t i = 0; i < layer.channels.size(); ++i)
      PyTuple_SetItem(channels.get(), Py_ssize_t(i), check(toPython(layer.channels[i])));  // Steals.
    char* target = nullptr;
    Reference pixels = uninitialisedBytes(layer.pixels.size() * sizeof(float), target);
    copies.emplace_back(target, &layer.pixels);
    Reference entry(check(PyTuple_Pack(2, channels.get(), pixels.get())));
    setItem(layers.get(), layer.name.c_str(), std::move(entry));
  }
  Reference dictionary(check(PyDict_New()));
  if (request.display && request.displayTarget) {
    PyObject* target = request.displayObject.get();
    Py_INCREF(target);
    setItem(dictionary.get(), "display", Reference(target));
  } else if (request.display) {
    char* target = nullptr;
    Reference display = uninitialisedBytes(outcome.display.size() * sizeof(float), target);
    copies.emplace_back(target, &outcome.display);
    setItem(dictionary.get(), "display", std::move(display));
  }
  Py_BEGIN_ALLOW_THREADS for (const auto& [target, source] : copies)
      std::memcpy(target, source->data(), source->size() * sizeof(float));
  Py_END_ALLOW_THREADS setItem(dictionary.get(), "width", Reference(check(PyLong_FromLong(result.width))));
  setItem(dictionary.get(), "height", Reference(check(PyLong_FromLong(result.height))));
  nlohmann::json stats = result.stats.toJson();
  if (outcome.exrWriteMilliseconds >= 0.0) stats["exr_write_ms"] = outcome.exrWriteMilliseconds;
  setItem(dictionary.get(), "stats", Reference(check(toPython(stats))));
  setItem(dictionary.get(), "layers", std::move(layers));
  return dictionary.release();
}

}  // namespace spindrift::python
