// The OpenImageIO plugin: reads every image format but OpenEXR's (PNG, JPEG, TIFF, ...). It is built as its
// own library (libspindrift_oiio.so, opened by io/OtherImageFormats.cpp on the first such file), so that a
// process that reads and writes OpenEXR alone never loads OpenImageIO's 261 libraries (0.2 s of every start,
// docs/frame-cost.md). The Python module links it in: Blender has loaded OpenImageIO already.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include "io/ImageFileErrors.h"
#include "io/ImageReader.h"
#include "io/ImageWindows.h"
#include "spindrift/Limits.h"

namespace spindrift {
namespace {

using image_file_errors::fail;
using image_file_errors::oneLine;

class OiioImageReader final : public ImageReader {
 public:
  explicit OiioImageReader(const std::filesystem::path& path) : path_(path) {
    // Keep unassociated alpha (PNG, TIFF) as stored: OIIO would otherwise premultiply the sRGB-encoded
    // values, and premultiplying is only right after decoding to linear.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    input_ = OIIO::ImageInput::open(path.string(), &config);
    if (!input_) fail(path, "cannot read image: " + oneLine(OIIO::geterror()));
    for (int subimage = 0; input_->seek_subimage(subimage, 0); ++subimage)
      specs_.push_back(input_->spec());
  }

  int imageCount() const override { return int(specs_.size()); }
  const std::vector<std::string>& channelNames(int image) const override {
    return specs_.at(std::size_t(image)).channelnames;
  }

  ColorEncoding colorEncoding(int image) const override {
    const OIIO::ImageSpec& spec = specs_.at(std::size_t(image));
    const std::string colorSpace = spec.get_string_attribute("oiio:ColorSpace");
    ColorEncoding encoding;
    encoding.srgb = OIIO::Strutil::iequals(colorSpace, "sRGB");
    if (OIIO::Strutil::istarts_with(colorSpace, "Gamma"))
      encoding.gamma = spec.get_float_attribute("oiio:Gamma", 1);
    encoding.unassociatedAlpha = spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
    return encoding;
  }

  FloatImage readChannels(int image, const std::vector<int>& channels, float missingValue) override {
    const OIIO::ImageSpec& spec = specs_.at(std::size_t(image));
    if (spec.deep) fail(path_, "deep images are not supported");
    const bool hasDisplayWindow = spec.full_width > 0 && spec.full_height > 0;
    const PixelWindow data{spec.x, spec.y, spec.width, spec.height};
    const ImageWindows windows = checkedWindows(
        path_, data,
        hasDisplayWindow ? PixelWindow{spec.full_x, spec.full_y, spec.full_width, spec.full_height} : data);

    int firstChannel = spec.nchannels;
    int lastChannel = -1;
    for (int channel : channels) {
      if (channel < 0) continue;
      firstChannel = std::min(firstChannel, channel);
      lastChannel = std::max(lastChannel, channel);
    }
    const int blockChannels = std::max(0, lastChannel + 1 - firstChannel);
    // OpenImageIO 2.4 converts a scanline image through a buffer of a chunk of rows, about 256 of them
    // however few the image has (fuzz_background_image: a 4,259,848 x 6 image made it allocate 13 GB, 3,072
    // bytes a column for three float channels), so that buffer counts too, at the file's channels and 4 bytes
    // each.
    constexpr std::uint64_t kConversionRows = 256;
    const std::uint64_t dataPixels = std::uint64_t(data.width) * std::uint64_t(data.height);
    const std::uint64_t displayPixels =
        std::uint64_t(windows.display.width) * std::uint64_t(windows.display.height);
    requireMemory((dataPixels * std::uint64_t(blockChannels) + displayPixels * channels.size() +
                   std::uint64_t(data.width) * kConversionRows *
                       std::uint64_t(std::max(blockChannels, spec.nchannels))) *
                      sizeof(float),
                  path_.string() + ": a " + std::to_string(windows.display.width) + "x" +
                      std::to_string(windows.display.height) + " image");
    std::vector<float> block(dataPixels * std::size_t(blockChannels));
    if (blockChannels > 0 &&
        !input_->read_image(image, 0, firstChannel, lastChannel + 1, OIIO::TypeFloat, block.data())) {
      fail(path_, "cannot read pixels: " + oneLine(input_->geterror()));
    }
    std::vector<int> slots;
    for (int channel : channels)
      slots.push_back(channel < 0 ? -1 : channel - firstChannel);
    return placeInDisplayWindow(windows, block, blockChannels, slots, missingValue);
  }

 private:
  std::filesystem::path path_;
  std::unique_ptr<OIIO::ImageInput> input_;
  std::vector<OIIO::ImageSpec> specs_;
};

}  // namespace
}  // namespace spindrift

/// The plugin's one entry point (io/OtherImageFormats.cpp): opens `path` or throws spindrift::Error.
extern "C" spindrift::ImageReader* spindrift_open_image_with_oiio(const char* path) {
  return new spindrift::OiioImageReader(path);
}
