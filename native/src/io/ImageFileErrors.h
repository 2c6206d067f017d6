#pragma once

#include <algorithm>
#include <filesystem>
#include <string>

#include "spindrift/Error.h"

namespace spindrift::image_file_errors {

/// Throws the one-line Error every image reader and writer reports: "<file>: <what went wrong>".
[[noreturn]] inline void fail(const std::filesystem::path& path, const std::string& what) {
  throw Error(path.string() + ": " + what);
}

/// OpenEXR's and OpenImageIO's messages may span lines; an Error is one line.
inline std::string oneLine(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  while (!message.empty() && message.back() == ' ')
    message.pop_back();
  return message.empty() ? "unknown error" : message;
}

}  // namespace spindrift::image_file_errors
