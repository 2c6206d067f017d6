#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "spindrift/FloatImage.h"

namespace spindrift {

/// How an image's colour is stored, so that it can be brought to linear and premultiplied.
struct ColorEncoding {
  bool srgb = false;               // sRGB's transfer function
  float gamma = 1.0f;              // a plain power law (1: none)
  bool unassociatedAlpha = false;  // colour not yet multiplied by alpha (PNG, TIFF)
};

/// One image file opened for reading: its images (OpenEXR's parts, other formats' subimages), each with
/// its channels' names, read as 32-bit floats on request. Readers throw Error naming the file.
class ImageReader {
 public:
  virtual ~ImageReader() = default;

  virtual int imageCount() const = 0;
  virtual const std::vector<std::string>& channelNames(int image) const = 0;
  virtual ColorEncoding colorEncoding(int image) const = 0;
  /// The listed channels (indices into channelNames; -1 gives `missingValue`) interleaved, over the image's
  /// display window, top row first. Pixels outside its data window are 0.
  virtual FloatImage readChannels(int image, const std::vector<int>& channels, float missingValue) = 0;
};

/// An OpenEXR file, read with OpenEXR itself (io/ExrReader.cpp).
std::unique_ptr<ImageReader> openExrImage(const std::filesystem::path& path);

/// Any other format OpenImageIO reads (PNG, JPEG, TIFF, ...), through the OpenImageIO plugin
/// (io/OtherImageFormats.cpp): OpenImageIO and its 261 libraries are loaded only when such a file is read.
std::unique_ptr<ImageReader> openOtherImage(const std::filesystem::path& path);

/// True when the file starts with OpenEXR's magic number.
bool isExrFile(const std::filesystem::path& path);

}  // namespace spindrift
