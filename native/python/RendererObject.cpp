// `_spindrift.Renderer`: one native Renderer (its own GL thread and EGL context) kept alive across frames.
// Calls are serialised by a lock taken with the GIL released, and the GIL stays released while a frame
// renders or is written, so a Python thread can render while Blender's UI runs.

#include "RendererObject.h"

#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <utility>

#include <exception>
#include <filesystem>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "FrameArguments.h"
#include "PythonErrors.h"
#include "PythonValues.h"
#include "Readback.h"
#include "ResultCrop.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Error.h"
#include "spindrift/Output.h"
#include "spindrift/Renderer.h"

namespace spindrift::python {
namespace {

struct RendererObject {
  PyObject_HEAD std::mutex* lock;  // Made in tp_new, so close and dealloc can rely on it.
  Renderer* renderer;              // Null before __init__ succeeds and after close().
};

// Runs `work` with the GIL released and this renderer's lock held; rethrows its exception with the GIL back.
template <typename Work>
void withoutGil(RendererObject* self, Work&& work) {
  std::exception_ptr failure;
  Py_BEGIN_ALLOW_THREADS try {
    std::lock_guard<std::mutex> guard(*self->lock);
    work();
  } catch (...) {
    failure = std::current_exception();
  }
  Py_END_ALLOW_THREADS if (failure) std::rethrow_exception(failure);
}

// `shaders/` beside the module file (the add-on's layout); else where the library looks on its own
// ($SPINDRIFT_SHADER_DIR, or share/spindrift/shaders beside the build or install tree's lib/).
std::filesystem::path defaultShaderDirectory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&addRendererType), &info) && info.dli_fname) {
    const std::filesystem::path beside = std::filesystem::path(info.dli_fname).parent_path() / "shaders";
    if (std::filesystem::is_directory(beside)) return beside;
  }
  return findShaderDirectory();
}

PyObject* rendererNew(PyTypeObject* type, PyObject*, PyObject*) {
  auto allocate = reinterpret_cast<allocfunc>(PyType_GetSlot(type, Py_tp_alloc));
  PyObject* object = allocate(type, 0);
  if (!object) return nullptr;
  auto* self = reinterpret_cast<RendererObject*>(object);
  self->renderer = nullptr;
  self->lock = new (std::nothrow) std::mutex;
  if (!self->lock) {
    Py_DECREF(object);
    return PyErr_NoMemory();
  }
  return object;
}

void closeRenderer(RendererObject* self) {
  withoutGil(self, [&] {
    delete self->renderer;  // Finishes queued GL work, destroys the context, joins the GL thread.
    self->renderer = nullptr;
  });
}

int rendererInit(PyObject* object, PyObject* args, PyObject* kwargs) {
  auto* self = reinterpret_cast<RendererObject*>(object);
  static const char* keywords[] = {"shader_dir", nullptr};
  const char* shaderDir = nullptr;
  if (!PyArg_ParseTupleAndKeywords(args, kwargs, "|z", const_cast<char**>(keywords), &shaderDir)) return -1;
  try {
    closeRenderer(self);
    const std::filesystem::path directory =
        shaderDir ? std::filesystem::path(shaderDir) : defaultShaderDirectory();
    if (!std::filesystem::is_directory(directory))
      throw Error("shader_dir " + directory.string() + " is not a directory");
    withoutGil(self, [&] { self->renderer = new Renderer(directory); });
    return 0;
  } catch (...) {
    raiseCurrentException();
    return -1;
  }
}

void rendererDealloc(PyObject* object) {
  auto* self = reinterpret_cast<RendererObject*>(object);
  PyTypeObject* type = Py_TYPE(object);
  if (self->lock) {
    try {
      closeRenderer(self);
    } catch (...) {
      // Nothing can be reported from a destructor; the GL thread is gone either way.
    }
    delete self->lock;
  }
  auto free = reinterpret_cast<freefunc>(PyType_GetSlot(type, Py_tp_free));
  free(object);
  Py_DECREF(type);  // Instances of heap types own a reference to their type.
}

PyObject* rendererClose(PyObject* object, PyObject*) {
  try {
    closeRenderer(reinterpret_cast<RendererObject*>(object));
    Py_RETURN_NONE;
  } catch (...) {
    return raiseCurrentException();
  }
}

PyObject* rendererEnter(PyObject* object, PyObject*) {
  Py_INCREF(object);
  return object;
}

PyObject* rendererExit(PyObject* object, PyObject*) {
  return rendererClose(object, nullptr);
}

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

// The layers the frame must render: those returned and those written, or every layer when either set is
// "all". Passes that feed none of them are not run at all (Renderer::setLayers), which is what makes a frame
// that only needs the compositor's six layers cheaper than a full one.
std::vector<std::string> layersToRender(const std::optional<std::vector<std::string>>& returned,
                                        const std::optional<std::vector<std::string>>& written,
                                        bool writing) {
  if (!returned || (writing && !written)) return {};  // Empty: all.
  std::vector<std::string> names = *returned;
  if (writing)
    for (const std::string& name : *written)
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  return names;
}

// The result's layers named in `written` (all when it is None), as a copy: called only when some must be left
// out.
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

// {"width", "height", "stats", "layers": {name: (channels, float32 bytes)}}, only the layers asked for.
PyObject* resultToPython(const RenderResult& result, const std::optional<std::vector<std::string>>& wanted,
                         double exrWriteMilliseconds) {
  std::set<std::string> available;
  for (const ImageLayer& layer : result.layers)
    available.insert(layer.name);
  for (const std::string& name : wanted.value_or(std::vector<std::string>{})) {
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
  std::vector<std::pair<char*, const ImageLayer*>> copies;
  for (const ImageLayer& layer : result.layers) {
    if (wanted && std::find(wanted->begin(), wanted->end(), layer.name) == wanted->end()) continue;
    Reference channels(check(PyTuple_New(Py_ssize_t(layer.channels.size()))));
    for (std::size_t i = 0; i < layer.channels.size(); ++i)
      PyTuple_SetItem(channels.get(), Py_ssize_t(i), check(toPython(layer.channels[i])));  // Steals.
    Reference pixels(
        check(PyBytes_FromStringAndSize(nullptr, Py_ssize_t(layer.pixels.size() * sizeof(float)))));
    copies.emplace_back(checkBytes(PyBytes_AsString(pixels.get())), &layer);
    Reference entry(check(PyTuple_Pack(2, channels.get(), pixels.get())));
    setItem(layers.get(), layer.name.c_str(), std::move(entry));
  }
  Py_BEGIN_ALLOW_THREADS for (const auto& [target, layer] : copies)
      std::memcpy(target, layer->pixels.data(), layer->pixels.size() * sizeof(float));
  Py_END_ALLOW_THREADS Reference dictionary(check(PyDict_New()));
  setItem(dictionary.get(), "width", Reference(check(PyLong_FromLong(result.width))));
  setItem(dictionary.get(), "height", Reference(check(PyLong_FromLong(result.height))));
  nlohmann::json stats = result.stats.toJson();
  if (exrWriteMilliseconds >= 0.0) stats["exr_write_ms"] = exrWriteMilliseconds;
  setItem(dictionary.get(), "stats", Reference(check(toPython(stats))));
  setItem(dictionary.get(), "layers", std::move(layers));
  return dictionary.release();
}

PyObject* rendererRender(PyObject* object, PyObject* args, PyObject* kwargs) {
  auto* self = reinterpret_cast<RendererObject*>(object);
  static const char* keywords[] = {"scene_json",     "frame",           "base_dir", "particles", "occluders",
                                   "liquid_mesh",    "background",      "exr_path", "layers",    "exr_layers",
                                   "exr_half_color", "exr_compression", "crop",     nullptr};
  const char* sceneJson = nullptr;
  int frame = 0;
  const char* baseDir = "";
  PyObject *particles = Py_None, *occluders = Py_None, *liquidMesh = Py_None, *background = Py_None;
  const char* exrPath = nullptr;
  PyObject *layers = Py_None, *exrLayers = Py_None, *crop = Py_None;
  int exrHalfColor = 0;
  const char* exrCompression = "zip";
  if (!PyArg_ParseTupleAndKeywords(args, kwargs, "si|$sOOOOzOOpsO", const_cast<char**>(keywords), &sceneJson,
                                   &frame, &baseDir, &particles, &occluders, &liquidMesh, &background,
                                   &exrPath, &layers, &exrLayers, &exrHalfColor, &exrCompression, &crop))
    return nullptr;
  try {
    // Relative paths in the scene are anchored at base_dir; messages name the scene "<base_dir>/scene_json".
    const std::filesystem::path anchor = std::filesystem::path(*baseDir ? baseDir : ".") / "scene_json";
    Scene scene = parseScene(sceneJson, anchor);
    FrameInputs inputs;
    if (particles != Py_None) inputs.particles = readParticles(particles);
    if (occluders != Py_None) {
      if (PyList_Check(occluders)) {
        for (Py_ssize_t i = 0; i < PyList_Size(occluders); ++i)
          inputs.occluders.push_back(readTriangleMesh(PyList_GetItem(occluders, i),
                                                      ("occluders[" + std::to_string(i) + "]").c_str()));
      } else {
        inputs.occluders.push_back(readTriangleMesh(occluders, "occluders"));
      }
    }
    if (liquidMesh != Py_None) inputs.liquidMesh = readTriangleMesh(liquidMesh, "liquid_mesh");
    if (background != Py_None) {
      // The in-memory background replaces the scene's background files (an environment and liquid_depth
      // stay).
      scene.background.image.clear();
      scene.background.depth.clear();
      scene.background.depthExplicit = false;
      readBackground(background, scene.camera, inputs);
    }
    const std::optional<std::vector<std::string>> layerNames = readLayerNames(layers, "layers");
    const std::optional<std::vector<std::string>> exrLayerNames = readLayerNames(exrLayers, "exr_layers");
    const std::optional<std::filesystem::path> exr =
        exrPath ? std::optional<std::filesystem::path>(exrPath) : std::nullopt;
    const ExrOptions exrOptions{exrHalfColor != 0, exrCompression,
                                exrLayerNames.value_or(std::vector<std::string>{})};
    const std::optional<CropWindow> window = readCropWindow(crop, scene.camera);
    std::optional<RenderResult> result;
    double exrWriteMilliseconds = -1.0;  // Reported in stats as exr_write_ms when a file was written.
    withoutGil(self, [&] {
      if (!self->renderer) throw Error("the renderer is closed");
      // Every call sets its own selection: the Renderer keeps it, and calls may ask for different layers.
      self->renderer->setLayers(layersToRender(layerNames, exrLayerNames, exr.has_value()));
      result = self->renderer->renderFrame(scene, frame, inputs);
      if (window) cropResult(*result, *window);
      if (!exr) return;
      const auto writeStart = std::chrono::steady_clock::now();
      writeExr(*result, *exr, exrOptions);
      exrWriteMilliseconds =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - writeStart).count();
    });
    return resultToPython(*result, layerNames, exrWriteMilliseconds);
  } catch (...) {
    return raiseCurrentException();
  }
}

// The GL strings, or a Python exception when the renderer is closed.
PyObject* glString(PyObject* object, bool version) {
  auto* self = reinterpret_cast<RendererObject*>(object);
  try {
    std::string text;
    withoutGil(self, [&] {
      if (!self->renderer) throw Error("the renderer is closed");
      text = version ? self->renderer->glVersion() : self->renderer->glRenderer();
    });
    return toPython(text);
  } catch (...) {
    return raiseCurrentException();
  }
}
PyObject* getGlRenderer(PyObject* object, void*) {
  return glString(object, false);
}
PyObject* getGlVersion(PyObject* object, void*) {
  return glString(object, true);
}

PyMethodDef rendererMethods[] = {
    {"render", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(rendererRender)),
     METH_VARARGS | METH_KEYWORDS,
     "render(scene_json, frame, *, base_dir='', particles=None, occluders=None, liquid_mesh=None, "
     "background=None, exr_path=None, layers=None, exr_layers=None, exr_half_color=False, "
     "exr_compression='zip', crop=None) -> dict\n\nRenders one frame; see docs/python-module.md."},
    {"close", rendererClose, METH_NOARGS, "Releases the native renderer (its GL thread and context) now."},
    {"__enter__", rendererEnter, METH_NOARGS, nullptr},
    {"__exit__", rendererExit, METH_VARARGS, nullptr},
    {nullptr, nullptr, 0, nullptr}};

PyGetSetDef rendererProperties[] = {
    {"gl_renderer", getGlRenderer, nullptr, "GL_RENDERER of the renderer's context.", nullptr},
    {"gl_version", getGlVersion, nullptr, "GL_VERSION of the renderer's context.", nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

const char rendererDoc[] =
    "Renderer(shader_dir=None)\n\nOwns a native renderer: its own GL thread and EGL context (the caller's GL "
    "context is never touched). shader_dir defaults to shaders/ beside the module. Raises Error when no "
    "OpenGL 4.5 context can be made.";

PyType_Slot rendererSlots[] = {{Py_tp_new, reinterpret_cast<void*>(rendererNew)},
                               {Py_tp_init, reinterpret_cast<void*>(rendererInit)},
                               {Py_tp_dealloc, reinterpret_cast<void*>(rendererDealloc)},
                               {Py_tp_methods, rendererMethods},
                               {Py_tp_getset, rendererProperties},
                               {Py_tp_doc, const_cast<char*>(rendererDoc)},
                               {0, nullptr}};

PyType_Spec rendererSpec = {"_spindrift.Renderer", sizeof(RendererObject), 0, Py_TPFLAGS_DEFAULT,
                            rendererSlots};

}  // namespace

bool addRendererType(PyObject* module) {
  PyObject* type = PyType_FromSpec(&rendererSpec);
  if (!type) return false;
  if (PyModule_AddObject(module, "Renderer", type) != 0) {
    Py_DECREF(type);
    return false;
  }
  return true;
}

}  // namespace spindrift::python
