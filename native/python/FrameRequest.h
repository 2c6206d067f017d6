#pragma once

// One frame as Renderer.render and Renderer.submit take it: read from the Python arguments with the GIL
// (every array copied), rendered without it, and turned back into the dict the caller gets.

#include <Python.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ArrayArgument.h"
#include "PythonErrors.h"
#include "ResultCrop.h"
#include "spindrift/FrameInputs.h"
#include "spindrift/Output.h"
#include "spindrift/RenderResult.h"
#include "spindrift/Renderer.h"
#include "spindrift/Scene.h"

namespace spindrift::python {

struct FrameRequest {
  Scene scene;
  int frame = 0;
  FrameInputs inputs;
  std::optional<std::vector<std::string>> layers;     ///< Returned; nullopt: all.
  std::optional<std::vector<std::string>> exrLayers;  ///< Written; nullopt: all.
  std::optional<std::filesystem::path> exrPath;
  ExrOptions exrOptions;
  std::optional<CropWindow> crop;
  bool display = false;  ///< Also return the viewport's display image (DisplayImage.h).
  /// `display_into`: the caller's float32 array the display image is written into by the rendering thread,
  /// held (buffer and reference) until the request goes, which must happen with the GIL.
  std::unique_ptr<ArrayArgument> displayTarget;
  Reference displayObject;
};

struct FrameOutcome {
  RenderResult result;
  double exrWriteMilliseconds = -1.0;  ///< Reported in stats as exr_write_ms when a file was written.
  std::vector<float> display;          ///< Empty unless the request asked for it.
};

/// Reads render()'s arguments (docs/python-module.md). Throws ArgumentError or PythonErrorSet.
FrameRequest readFrameRequest(PyObject* args, PyObject* kwargs);

/// Renders the request on `renderer` (and writes its EXR). Touches no Python object: runs without the GIL.
FrameOutcome renderRequest(Renderer& renderer, const FrameRequest& request);

/// The dict render() returns: {"width", "height", "stats", "layers"} and, when asked, "display": a new bytes
/// object, or the request's `display_into` array, already filled. Needs the GIL.
PyObject* outcomeToPython(const FrameOutcome& outcome, const FrameRequest& request);

}  // namespace spindrift::python
