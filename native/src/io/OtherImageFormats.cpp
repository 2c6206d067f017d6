#include <dlfcn.h>

#include <memory>
#include <mutex>
#include <string>

#include "io/ImageFileErrors.h"
#include "io/ImageReader.h"

// Defined by the OpenImageIO plugin (io/oiio/OiioImageReader.cpp). Weak: where the plugin's code is linked in
// (the Python module) this is it; in libspindrift.so it stays null and the plugin is opened beside it.
extern "C" spindrift::ImageReader* spindrift_open_image_with_oiio(const char* path) __attribute__((weak));

namespace spindrift {
namespace {

using OpenFunction = ImageReader* (*)(const char*);

// The plugin's file, libspindrift_oiio.so in the directory this library was loaded from.
std::filesystem::path pluginPath() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&pluginPath), &info) == 0 || info.dli_fname == nullptr)
    return "libspindrift_oiio.so";
  return std::filesystem::path(info.dli_fname).parent_path() / "libspindrift_oiio.so";
}

// Opened once per process and kept: its readers' code must outlive every reader.
OpenFunction openFunction(const std::filesystem::path& image) {
  static std::mutex mutex;
  static OpenFunction function = nullptr;
  static std::string failure;
  std::lock_guard<std::mutex> lock(mutex);
  if (function == nullptr && failure.empty()) {
    if (spindrift_open_image_with_oiio != nullptr) {
      function = spindrift_open_image_with_oiio;
    } else {
      const std::filesystem::path path = pluginPath();
      void* plugin = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      void* symbol = plugin ? dlsym(plugin, "spindrift_open_image_with_oiio") : nullptr;
      if (symbol) {
        function = reinterpret_cast<OpenFunction>(symbol);
      } else {
        const char* why = dlerror();
        failure = "formats other than OpenEXR are read by OpenImageIO through " + path.string() +
                  ", which cannot be loaded: " + (why ? why : "no entry point");
      }
    }
  }
  if (function == nullptr) image_file_errors::fail(image, failure);
  return function;
}

}  // namespace

std::unique_ptr<ImageReader> openOtherImage(const std::filesystem::path& path) {
  return std::unique_ptr<ImageReader>(openFunction(path)(path.c_str()));
}

}  // namespace spindrift
