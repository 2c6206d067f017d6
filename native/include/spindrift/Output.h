#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "spindrift/RenderResult.h"

namespace spindrift {

/// How writeExr stores the pixels. The defaults (every channel 32-bit float, ZIP at level 1) are the command
/// line's and the Python module's.
struct ExrOptions {
  /// Colour layers as 16-bit half float. Layers whose values are positions stay 32-bit float (see
  /// exrLayerNeedsFloat): a half's 11-bit mantissa would move a refraction UV by up to ~1 px at 1920 px.
  bool halfColor = false;
  /// An OpenEXR compression: "none", "zip", "zips", "piz", "rle", "dwaa", ... (OpenImageIO's names); ZIP
  /// may name zlib's level ("zip:1"). Level 1 writes the examples' frames 4-5 % larger than OpenEXR's
  /// default (4) in half the time (docs/farm.md); reading is as fast.
  std::string compression = "zip:1";
  /// The layers to write (by name, in the result's order); empty: every layer.
  std::vector<std::string> layers;
};

/// True for one of OpenEXR's compressions as OpenImageIO names them ("none", "rle", "zip", "zips",
/// "piz", "pxr24", "b44", "b44a", "dwaa", "dwab"), or "zip:N" / "zips:N" with zlib's level N from 1 (fastest)
/// to 9.
bool exrCompressionIsValid(const std::string& compression);

/// True for the layers writeExr keeps in 32-bit float under `halfColor`: depths (eye depth in scene units,
/// and the 1e10 "nothing" value, which half cannot hold) and `refraction_uv` (image coordinates).
bool exrLayerNeedsFloat(const std::string& layerName);

/// Writes the layers (every one, or those `options.layers` names) as one multilayer OpenEXR (channels
/// "layer.channel"). The file is written under a
/// temporary name beside the target and renamed, so a failed write never replaces a good file. Throws Error
/// for an unknown compression.
void writeExr(const RenderResult& result, const std::filesystem::path& path, const ExrOptions& options = {});
/// Writes the composite layer as 8-bit sRGB PNG (alpha kept), also through a temporary name.
void writePng(const RenderResult& result, const std::filesystem::path& path);

}  // namespace spindrift
