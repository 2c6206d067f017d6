#include "gl/EglContext.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glew.h>

#include <cstring>
#include <vector>

#include "gl/EglLibrary.h"
#include "spindrift/Error.h"

namespace spindrift {
namespace {

struct Attempt {
  std::string route;
  EGLDisplay display = EGL_NO_DISPLAY;
};

bool hasExtension(const char* extensions, const char* name) {
  if (!extensions) return false;
  const std::size_t length = std::strlen(name);
  for (const char* at = std::strstr(extensions, name); at; at = std::strstr(at + 1, name))
    if ((at == extensions || at[-1] == ' ') && (at[length] == ' ' || at[length] == '\0')) return true;
  return false;
}

std::string eglErrorName(EGLint error) {
  switch (error) {
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default:
      return "EGL error " + std::to_string(error);
  }
}

// Hardware devices first: on a machine with a GPU, Mesa's software device is the last resort.
// No display is ever terminated: EGL displays are shared by every context of the process (one per Renderer),
// and eglTerminate would pull the context from under another Renderer.
std::vector<Attempt> candidateDisplays() {
  std::vector<Attempt> attempts;
  const char* clientExtensions = egl().queryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(egl().getProcAddress("eglGetPlatformDisplayEXT"));
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(egl().getProcAddress("eglQueryDevicesEXT"));
  auto queryDeviceString =
      reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(egl().getProcAddress("eglQueryDeviceStringEXT"));
  if (getPlatformDisplay && queryDevices && hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
    EGLDeviceEXT devices[16];
    EGLint deviceCount = 0;
    if (queryDevices(16, devices, &deviceCount)) {
      std::vector<Attempt> software;
      for (EGLint i = 0; i < deviceCount; ++i) {
        const char* deviceExtensions =
            queryDeviceString ? queryDeviceString(devices[i], EGL_EXTENSIONS) : nullptr;
        Attempt attempt{"EGL device " + std::to_string(i),
                        getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr)};
        if (hasExtension(deviceExtensions, "EGL_MESA_device_software"))
          software.push_back(attempt);
        else
          attempts.push_back(attempt);
      }
      attempts.insert(attempts.end(), software.begin(), software.end());
    }
  }
  if (getPlatformDisplay && hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless"))
    attempts.push_back({"Mesa surfaceless",
                        getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr)});
  attempts.push_back({"default display", egl().getDisplay(EGL_DEFAULT_DISPLAY)});
  return attempts;
}

}  // namespace

EglContext::EglContext() {
  std::string failures;
  for (const Attempt& attempt : candidateDisplays()) {
    auto fail = [&](const std::string& what) {
      failures += (failures.empty() ? "" : "; ") + attempt.route + ": " + what;
    };
    if (attempt.display == EGL_NO_DISPLAY) {
      fail("no display");
      continue;
    }
    EGLint major = 0, minor = 0;
    if (!egl().initialize(attempt.display, &major, &minor)) {
      fail("eglInitialize " + eglErrorName(egl().getError()));
      continue;
    }
    if (!egl().bindAPI(EGL_OPENGL_API)) {
      fail("no desktop OpenGL");
      continue;
    }
    const char* displayExtensions = egl().queryString(attempt.display, EGL_EXTENSIONS);
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!hasExtension(displayExtensions, "EGL_KHR_no_config_context")) {
      const EGLint configAttributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                         EGL_OPENGL_BIT, EGL_NONE};
      EGLint configCount = 0;
      if (!egl().chooseConfig(attempt.display, configAttributes, &config, 1, &configCount) ||
          configCount == 0) {
        fail("no pbuffer config");
        continue;
      }
    }
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                        4,
                                        EGL_CONTEXT_MINOR_VERSION,
                                        5,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                        EGL_NONE};
    EGLContext context = egl().createContext(attempt.display, config, EGL_NO_CONTEXT, contextAttributes);
    if (context == EGL_NO_CONTEXT) {
      fail("no OpenGL 4.5 core context (" + eglErrorName(egl().getError()) + ")");
      continue;
    }
    EGLSurface surface = EGL_NO_SURFACE;
    if (!hasExtension(displayExtensions, "EGL_KHR_surfaceless_context")) {
      const EGLint pbufferAttributes[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
      surface = egl().createPbufferSurface(attempt.display, config, pbufferAttributes);
    }
    if (!egl().makeCurrent(attempt.display, surface, surface, context)) {
      fail("eglMakeCurrent " + eglErrorName(egl().getError()));
      if (surface != EGL_NO_SURFACE) egl().destroySurface(attempt.display, surface);
      egl().destroyContext(attempt.display, context);
      continue;
    }
    display_ = attempt.display;
    context_ = context;
    surface_ = surface;
    route_ = attempt.route;
    break;
  }
  if (!context_) throw Error("no OpenGL 4.5 context through EGL (" + failures + ")");

  // Debian's GLEW is built for GLX: under EGL, glewInit loads every GL entry point and then reports
  // GLEW_ERROR_NO_GLX_DISPLAY for the GLX part, which is no failure here.
  glewExperimental = GL_TRUE;
  const GLenum glewStatus = glewInit();
  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  if ((glewStatus != GLEW_OK && glewStatus != GLEW_ERROR_NO_GLX_DISPLAY) || !version || !glCreateTextures ||
      !glDispatchCompute) {
    release();
    throw Error("OpenGL entry points could not be loaded (GLEW status " + std::to_string(glewStatus) + ")");
  }
  while (glGetError() != GL_NO_ERROR) {
    // glewInit queries GL_EXTENSIONS the pre-core way, which a core context answers with GL_INVALID_ENUM.
  }
  version_ = version;
  renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
}

EglContext::~EglContext() {
  release();
}

void EglContext::release() {
  if (!display_) return;
  egl().makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (surface_) egl().destroySurface(display_, surface_);
  if (context_) egl().destroyContext(display_, context_);
  egl().releaseThread();
  display_ = context_ = surface_ = nullptr;
}

}  // namespace spindrift
