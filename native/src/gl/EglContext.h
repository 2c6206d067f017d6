#pragma once

#include <string>

namespace spindrift {

/// A headless OpenGL 4.5 core context through EGL, current on the thread that made it. It tries, in order,
/// EGL devices (hardware before Mesa's software device), Mesa's surfaceless platform and the default display,
/// and loads GL entry points with GLEW. Throws Error with one line that says what each attempt answered.
class EglContext {
 public:
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }
  /// Which EGL route gave the context, e.g. "EGL device 0" or "Mesa surfaceless".
  const std::string& route() const { return route_; }

 private:
  void release();

  void* display_ = nullptr;
  void* context_ = nullptr;
  void* surface_ = nullptr;
  std::string renderer_;
  std::string version_;
  std::string route_;
};

}  // namespace spindrift
