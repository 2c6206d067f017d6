#pragma once

#include <filesystem>

#include "spindrift/RenderResult.h"

namespace spindrift {

/// Writes every layer as one multilayer OpenEXR (channels "layer.channel", 32-bit float). The file is written
/// under a temporary name beside the target and renamed, so a failed write never replaces a good file.
void writeExr(const RenderResult& result, const std::filesystem::path& path);
/// Writes the composite layer as 8-bit sRGB PNG (alpha kept), also through a temporary name.
void writePng(const RenderResult& result, const std::filesystem::path& path);

}  // namespace spindrift
