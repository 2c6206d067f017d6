#pragma once

#include <cstdint>
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

/// Channels of one image to read together: indices into its channelNames, -1 for `missingValue`.
struct ChannelSet {
  std::vector<int> channels;
  float missingValue = 0.0f;
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
  /// Several sets of one image's channels, each as readChannels returns it. OpenEXR compresses every channel
  /// of a block of scanlines together, so each readChannels call decodes the whole image; its reader decodes
  /// it once here (a background with Cycles' light passes, read pass by pass, was decoded eight times:
  /// docs/frame-cost.md, session 52). Other formats read each set in turn.
  virtual std::vector<FloatImage> readChannelSets(int image, const std::vector<ChannelSet>& sets) {
    std::vector<FloatImage> images;
    for (const ChannelSet& set : sets)
      images.push_back(readChannels(image, set.channels, set.missingValue));
    return images;
  }
};

/// The decoded channels an OpenEXR reader holds at once: an image whose channels read together take more is
/// decoded in bands of rows (a multiple of 256, which every scanline compression's block of rows divides).
constexpr std::uint64_t kExrDecodeBandBytes = 64ull << 20;

/// An OpenEXR file, read with OpenEXR itself (io/ExrReader.cpp); `decodeBandBytes` for tests.
std::unique_ptr<ImageReader> openExrImage(const std::filesystem::path& path,
                                          std::uint64_t decodeBandBytes = kExrDecodeBandBytes);

/// Any other format OpenImageIO reads (PNG, JPEG, TIFF, ...), through the OpenImageIO plugin
/// (io/OtherImageFormats.cpp): OpenImageIO and its 261 libraries are loaded only when such a file is read.
std::unique_ptr<ImageReader> openOtherImage(const std::filesystem::path& path);

/// True when the file starts with OpenEXR's magic number.
bool isExrFile(const std::filesystem::path& path);

}  // namespace spindrift
