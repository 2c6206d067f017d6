#include "gl/EglLibrary.h"

#include <dlfcn.h>

#include <mutex>
#include <string>

#include "spindrift/Error.h"

namespace spindrift {
namespace {

template <typename Function>
void load(void* library, const char* name, Function& function) {
  function = reinterpret_cast<Function>(dlsym(library, name));
  if (!function) throw Error(std::string("libEGL.so.1 has no ") + name);
}

EglLibrary open() {
  void* library = dlopen("libEGL.so.1", RTLD_NOW | RTLD_GLOBAL);
  if (!library)
    throw Error(
        std::string("cannot load EGL (") + dlerror() +
        "): install libegl1 and libegl-mesa0 (apt-get install libegl1 libegl-mesa0), or a GPU driver's EGL");
  EglLibrary functions{};
  load(library, "eglBindAPI", functions.bindAPI);
  load(library, "eglChooseConfig", functions.chooseConfig);
  load(library, "eglCreateContext", functions.createContext);
  load(library, "eglCreatePbufferSurface", functions.createPbufferSurface);
  load(library, "eglDestroyContext", functions.destroyContext);
  load(library, "eglDestroySurface", functions.destroySurface);
  load(library, "eglGetDisplay", functions.getDisplay);
  load(library, "eglGetError", functions.getError);
  load(library, "eglGetProcAddress", functions.getProcAddress);
  load(library, "eglInitialize", functions.initialize);
  load(library, "eglMakeCurrent", functions.makeCurrent);
  load(library, "eglQueryString", functions.queryString);
  load(library, "eglReleaseThread", functions.releaseThread);
  return functions;
}

}  // namespace

const EglLibrary& egl() {
  // A failed load is retried on the next call (the user may install EGL while Blender runs).
  static std::mutex mutex;
  static bool loaded = false;
  static EglLibrary functions{};
  std::lock_guard<std::mutex> lock(mutex);
  if (!loaded) {
    functions = open();
    loaded = true;
  }
  return functions;
}

}  // namespace spindrift
