// `_spindrift.Renderer`: one native Renderer (its own GL thread and EGL context) kept alive across frames.
// Calls are serialised by a lock taken with the GIL released, and the GIL stays released while a frame
// renders or is written, so a Python thread can render while Blender's UI runs. submit() renders on a native
// thread instead, so a host can render in the background without running Python off its main thread (Blender
// is not safe with that: docs/blender.md).

#include "RendererObject.h"

#include <dlfcn.h>

#include <atomic>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "FrameRequest.h"
#include "PythonErrors.h"
#include "PythonValues.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Error.h"
#include "spindrift/Renderer.h"

namespace spindrift::python {
namespace {

// A frame handed to submit(): rendered on its own native thread, which touches no Python object, and
// collected by poll() on the caller's thread. Only one is in flight per Renderer.
struct InFlightFrame {
  FrameRequest request;
  FrameOutcome outcome;
  std::exception_ptr failure;
  std::atomic<bool> finished{false};
  std::thread thread;
};

struct RendererObject {
  PyObject_HEAD std::mutex* lock;  // Made in tp_new, so close and dealloc can rely on it.
  Renderer* renderer;              // Null before __init__ succeeds and after close().
  InFlightFrame* inFlight;         // The frame submit() started and poll() has not collected; or null.
};

// Waits for the frame in flight (with the GIL released) and takes it; null when there is none.
std::unique_ptr<InFlightFrame> joinInFlight(RendererObject* self) {
  std::unique_ptr<InFlightFrame> frame(self->inFlight);
  self->inFlight = nullptr;
  if (frame && frame->thread.joinable()) {
    Py_BEGIN_ALLOW_THREADS frame->thread.join();
    Py_END_ALLOW_THREADS
  }
  return frame;
}

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
  self->inFlight = nullptr;
  self->lock = new (std::nothrow) std::mutex;
  if (!self->lock) {
    Py_DECREF(object);
    return PyErr_NoMemory();
  }
  return object;
}

void closeRenderer(RendererObject* self) {
  joinInFlight(self);  // A frame in flight finishes (and is dropped) before its renderer goes.
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

PyObject* rendererRender(PyObject* object, PyObject* args, PyObject* kwargs) {
  auto* self = reinterpret_cast<RendererObject*>(object);
  try {
    const FrameRequest request = readFrameRequest(args, kwargs);
    std::optional<FrameOutcome> outcome;
    withoutGil(self, [&] {
      if (!self->renderer) throw Error("the renderer is closed");
      outcome = renderRequest(*self->renderer, request);
    });
    return outcomeToPython(*outcome, request);
  } catch (...) {
    return raiseCurrentException();
  }
}

PyObject* rendererSubmit(PyObject* object, PyObject* args, PyObject* kwargs) {
  auto* self = reinterpret_cast<RendererObject*>(object);
  try {
    if (self->inFlight)
      throw Error("a frame is already in flight on this renderer: collect it with poll() first");
    if (!self->renderer) throw Error("the renderer is closed");
    auto frame = std::make_unique<InFlightFrame>();
    frame->request = readFrameRequest(args, kwargs);
    InFlightFrame* running = frame.get();
    running->thread = std::thread([self, running] {
      try {
        std::lock_guard<std::mutex> guard(*self->lock);
        if (!self->renderer) throw Error("the renderer is closed");
        running->outcome = renderRequest(*self->renderer, running->request);
      } catch (...) {
        running->failure = std::current_exception();
      }
      running->finished.store(true, std::memory_order_release);
    });
    self->inFlight = frame.release();
    Py_RETURN_NONE;
  } catch (...) {
    return raiseCurrentException();
  }
}

PyObject* rendererPoll(PyObject* object, PyObject*) {
  auto* self = reinterpret_cast<RendererObject*>(object);
  try {
    if (!self->inFlight || !self->inFlight->finished.load(std::memory_order_acquire)) Py_RETURN_NONE;
    const std::unique_ptr<InFlightFrame> frame = joinInFlight(self);
    if (frame->failure) std::rethrow_exception(frame->failure);
    return outcomeToPython(frame->outcome, frame->request);
  } catch (...) {
    return raiseCurrentException();
  }
}

PyObject* getBusy(PyObject* object, void*) {
  auto* self = reinterpret_cast<RendererObject*>(object);
  return PyBool_FromLong(self->inFlight != nullptr &&
                         !self->inFlight->finished.load(std::memory_order_acquire));
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
     "exr_compression='zip:1', crop=None, display=False, display_into=None) -> dict\n\nRenders one frame; "
     "see "
     "docs/python-module.md."},
    {"submit", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(rendererSubmit)),
     METH_VARARGS | METH_KEYWORDS,
     "submit(scene_json, frame, **render's keywords) -> None\n\nStarts rendering one frame on a native "
     "thread and returns at once; poll() collects it. No Python runs while it renders."},
    {"poll", rendererPoll, METH_NOARGS,
     "poll() -> dict | None\n\nThe submitted frame's result (as render() returns it) once it has finished, "
     "else None; raises the frame's error instead when it failed. A result is returned once."},
    {"close", rendererClose, METH_NOARGS, "Releases the native renderer (its GL thread and context) now."},
    {"__enter__", rendererEnter, METH_NOARGS, nullptr},
    {"__exit__", rendererExit, METH_VARARGS, nullptr},
    {nullptr, nullptr, 0, nullptr}};

PyGetSetDef rendererProperties[] = {
    {"gl_renderer", getGlRenderer, nullptr, "GL_RENDERER of the renderer's context.", nullptr},
    {"gl_version", getGlVersion, nullptr, "GL_VERSION of the renderer's context.", nullptr},
    {"busy", getBusy, nullptr, "True while a submitted frame is rendering.", nullptr},
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
