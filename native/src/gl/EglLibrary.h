#pragma once

#include <EGL/egl.h>

namespace spindrift {

/// EGL's entry points, taken from libEGL.so.1 when the first context is made rather than when the library
/// loads: Debian's blender package does not bring EGL, and the add-on's module must still import there to
/// tell the user what to install.
struct EglLibrary {
  decltype(&::eglBindAPI) bindAPI;
  decltype(&::eglChooseConfig) chooseConfig;
  decltype(&::eglCreateContext) createContext;
  decltype(&::eglCreatePbufferSurface) createPbufferSurface;
  decltype(&::eglDestroyContext) destroyContext;
  decltype(&::eglDestroySurface) destroySurface;
  decltype(&::eglGetDisplay) getDisplay;
  decltype(&::eglGetError) getError;
  decltype(&::eglGetProcAddress) getProcAddress;
  decltype(&::eglInitialize) initialize;
  decltype(&::eglMakeCurrent) makeCurrent;
  decltype(&::eglQueryString) queryString;
  decltype(&::eglReleaseThread) releaseThread;
};

/// Opens libEGL.so.1 once (never closed); throws Error saying which packages provide it when it is missing.
const EglLibrary& egl();

}  // namespace spindrift
