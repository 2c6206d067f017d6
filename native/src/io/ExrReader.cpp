#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfPartType.h>

#include "io/ExrThreads.h"
#include "io/ImageFileErrors.h"
#include "io/ImageReader.h"
#include "io/ImageWindows.h"
#include "spindrift/Error.h"
#include "spindrift/Limits.h"

namespace spindrift {
namespace {

using image_file_errors::fail;
using image_file_errors::oneLine;

PixelWindow windowOf(const Imath::Box2i& box) {
  return {box.min.x, box.min.y, (long long)box.max.x - box.min.x + 1, (long long)box.max.y - box.min.y + 1};
}

class ExrReader final : public ImageReader {
 public:
  explicit ExrReader(const std::filesystem::path& path) : path_(path) {
    useEveryCoreForOpenExrUnlessTheHostChose();
    try {
      file_ = std::make_unique<Imf::MultiPartInputFile>(path.c_str());
    } catch (const std::exception& error) {
      fail(path, "cannot read image: " + oneLine(error.what()));
    }
    for (int part = 0; part < file_->parts(); ++part) {
      std::vector<std::string> names;
      const Imf::ChannelList& channels = file_->header(part).channels();
      for (auto channel = channels.begin(); channel != channels.end(); ++channel)
        names.push_back(channel.name());
      channelNames_.push_back(std::move(names));
    }
  }

  int imageCount() const override { return int(channelNames_.size()); }
  const std::vector<std::string>& channelNames(int image) const override { return channelNames_.at(image); }
  // OpenEXR stores linear, premultiplied colour.
  ColorEncoding colorEncoding(int) const override { return {}; }

  FloatImage readChannels(int image, const std::vector<int>& channels, float missingValue) override {
    const Imf::Header& header = file_->header(image);
    if (header.hasType() && Imf::isDeepData(header.type())) fail(path_, "deep images are not supported");
    const ImageWindows windows =
        checkedWindows(path_, windowOf(header.dataWindow()), windowOf(header.displayWindow()));

    // Each channel the caller names is read once (grey is asked for as R, G and B) into `block`, over the
    // data window.
    std::vector<int> distinct;
    for (int channel : channels)
      if (channel >= 0 && std::find(distinct.begin(), distinct.end(), channel) == distinct.end())
        distinct.push_back(channel);
    const std::uint64_t dataPixels = std::uint64_t(windows.data.width) * std::uint64_t(windows.data.height);
    const std::uint64_t displayPixels =
        std::uint64_t(windows.display.width) * std::uint64_t(windows.display.height);
    requireMemory((dataPixels * distinct.size() + displayPixels * channels.size()) * sizeof(float),
                  path_.string() + ": a " + std::to_string(windows.display.width) + "x" +
                      std::to_string(windows.display.height) + " image");
    std::vector<float> block(dataPixels * distinct.size());
    if (!distinct.empty()) {
      Imf::FrameBuffer frameBuffer;
      const std::size_t pixelStride = distinct.size() * sizeof(float);
      for (std::size_t slot = 0; slot < distinct.size(); ++slot) {
        const std::string& name = channelNames_[std::size_t(image)].at(std::size_t(distinct[slot]));
        const Imf::Channel& channel = header.channels()[name];
        if (channel.xSampling != 1 || channel.ySampling != 1)
          fail(path_, "channel " + name + " is subsampled, which is not supported");
        frameBuffer.insert(name,
                           Imf::Slice::Make(Imf::FLOAT, block.data() + slot, header.dataWindow(), pixelStride,
                                            pixelStride * std::size_t(windows.data.width)));
      }
      try {
        Imf::InputPart part(*file_, image);
        part.setFrameBuffer(frameBuffer);
        part.readPixels(header.dataWindow().min.y, header.dataWindow().max.y);
      } catch (const Error&) {
        throw;
      } catch (const std::exception& error) {
        fail(path_, "cannot read pixels: " + oneLine(error.what()));
      }
    }
    std::vector<int> slots;
    for (int channel : channels)
      slots.push_back(
          channel < 0 ? -1 : int(std::find(distinct.begin(), distinct.end(), channel) - distinct.begin()));
    return placeInDisplayWindow(windows, block, int(distinct.size()), slots, missingValue);
  }

 private:
  std::filesystem::path path_;
  std::unique_ptr<Imf::MultiPartInputFile> file_;
  std::vector<std::vector<std::string>> channelNames_;
};

}  // namespace

bool isExrFile(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  unsigned char magic[4] = {};
  file.read(reinterpret_cast<char*>(magic), sizeof(magic));
  return file.gcount() == 4 && magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01;
}

std::unique_ptr<ImageReader> openExrImage(const std::filesystem::path& path) {
  return std::make_unique<ExrReader>(path);
}

}  // namespace spindrift
