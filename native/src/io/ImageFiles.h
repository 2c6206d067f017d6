#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <vector>

#include "spindrift/FloatImage.h"

namespace spindrift {

class ImageReader;

/// Reads an image's colour as RGBA (alpha 1 where the file has none; grey repeated to RGB). In a multilayer
/// EXR the first layer named like "Combined" (Blender's "ViewLayer.Combined.R" ...) is taken; otherwise the
/// plain R, G, B, A channels. Colour comes back as Blender's Combined pass is: linear (sRGB and gamma encoded
/// files are decoded) with premultiplied alpha (unassociated alpha, as in PNG, is multiplied in after
/// decoding). Pixels outside an EXR's data window but inside its display window are 0. Throws Error naming
/// the file when it cannot be read or has no colour.
FloatImage readColorImage(const std::filesystem::path& path);

/// Reads planar eye depth as one channel: a channel named "Z" or ending in ".Z" whose layer looks like
/// depth ("Depth.Z", "ViewLayer.Depth.Z", "depth.Z", "Z"). Returns nothing when the file has no such channel.
std::optional<FloatImage> readDepthImage(const std::filesystem::path& path);

/// What the renderer reads from a background file, each of its images decoded once (OpenEXR compresses every
/// channel of a block of rows together; the file read by three readers in turn, the light passes pass by
/// pass, was decoded eight times: docs/frame-cost.md, session 52). Throws as readColorImage does.
struct BackgroundFile {
  /// As readColorImage reads it.
  FloatImage color;
  /// As readDepthImage reads it, when asked for (`withDepth`).
  std::optional<FloatImage> depth;
  /// Cycles' light passes (layers ending in DiffDir, DiffInd, DiffCol, GlossDir, GlossInd, GlossCol, as
  /// Blender writes them in a multilayer EXR) as three RGBA images: direct diffuse (DiffCol x DiffDir),
  /// direct glossy (GlossCol x GlossDir) and indirect light (DiffCol x DiffInd + GlossCol x GlossInd). The
  /// direct diffuse image's alpha holds DiffDir itself (the mean of its R, G, B), the light before the
  /// surface's colour. Nothing when any of the six is missing.
  std::optional<std::array<FloatImage, 3>> lightPasses;
};
BackgroundFile readBackgroundFile(const std::filesystem::path& path, bool withDepth);
/// The same from a file already open (`path` names it in errors).
BackgroundFile readBackgroundFile(ImageReader& input, const std::filesystem::path& path, bool withDepth);

/// Resamples to a new size: bilinear for colour, nearest for depth (`nearest`), so depth edges stay sharp.
FloatImage resizeImage(const FloatImage& image, int width, int height, bool nearest);

}  // namespace spindrift
