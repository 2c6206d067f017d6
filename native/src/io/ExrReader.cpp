#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
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

// The rows decoded at once: the whole data window while its decoded channels fit `bandBytes`, else bands of a
// multiple of 256 rows. Every scanline compression's block of rows divides 256 (DWAB's is 256), so no block
// is decoded twice, and a band is many blocks, which OpenEXR decodes on its threads.
constexpr long long kBandRowMultiple = 256;

long long rowsDecodedAtOnce(std::uint64_t rowFloats, long long dataRows, std::uint64_t bandBytes) {
  const std::uint64_t rowBytes = std::max<std::uint64_t>(1, rowFloats * sizeof(float));
  if (rowBytes * std::uint64_t(dataRows) <= bandBytes) return std::max(1LL, dataRows);
  const long long multiples = std::max<long long>(1, (long long)(bandBytes / rowBytes) / kBandRowMultiple);
  return std::min(dataRows, multiples * kBandRowMultiple);
}

class ExrReader final : public ImageReader {
 public:
  ExrReader(const std::filesystem::path& path, std::uint64_t decodeBandBytes)
      : path_(path), decodeBandBytes_(decodeBandBytes) {
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
    return std::move(readChannelSets(image, {ChannelSet{channels, missingValue}}).front());
  }

  std::vector<FloatImage> readChannelSets(int image, const std::vector<ChannelSet>& sets) override {
    const Imf::Header& header = file_->header(image);
    if (header.hasType() && Imf::isDeepData(header.type())) fail(path_, "deep images are not supported");
    const ImageWindows windows =
        checkedWindows(path_, windowOf(header.dataWindow()), windowOf(header.displayWindow()));

    // Each channel any set names is decoded once (grey is asked for as R, G and B), a band of rows at a
    // time into `block`, and placed into every set that names it.
    std::vector<int> distinct;
    std::size_t setChannels = 0;
    for (const ChannelSet& set : sets) {
      setChannels += set.channels.size();
      for (int channel : set.channels)
        if (channel >= 0 && std::find(distinct.begin(), distinct.end(), channel) == distinct.end())
          distinct.push_back(channel);
    }
    const std::uint64_t rowFloats = std::uint64_t(windows.data.width) * std::uint64_t(distinct.size());
    const long long rowsPerBand = rowsDecodedAtOnce(rowFloats, windows.data.height, decodeBandBytes_);
    const std::uint64_t displayPixels =
        std::uint64_t(windows.display.width) * std::uint64_t(windows.display.height);
    requireMemory((rowFloats * std::uint64_t(rowsPerBand) + displayPixels * setChannels) * sizeof(float),
                  path_.string() + ": a " + std::to_string(windows.display.width) + "x" +
                      std::to_string(windows.display.height) + " image");
    std::vector<FloatImage> images;
    std::vector<std::vector<int>> slots;
    for (const ChannelSet& set : sets) {
      images.push_back(emptyDisplayImage(windows, int(set.channels.size())));
      std::vector<int>& setSlots = slots.emplace_back();
      for (int channel : set.channels)
        setSlots.push_back(
            channel < 0 ? -1 : int(std::find(distinct.begin(), distinct.end(), channel) - distinct.begin()));
    }
    const auto place = [&](const float* block, long long firstRow, long long rows) {
      for (std::size_t s = 0; s < sets.size(); ++s)
        placeRowsInDisplayWindow(windows, block, int(distinct.size()), firstRow, rows, slots[s],
                                 sets[s].missingValue, &images[s]);
    };
    if (distinct.empty()) {
      place(nullptr, 0, windows.data.height);
      return images;
    }
    std::vector<float> block(rowFloats * std::uint64_t(rowsPerBand));
    const Imath::Box2i& dataWindow = header.dataWindow();
    const std::size_t pixelStride = distinct.size() * sizeof(float);
    try {
      Imf::InputPart part(*file_, image);
      for (long long firstRow = 0; firstRow < windows.data.height; firstRow += rowsPerBand) {
        const long long rows = std::min(rowsPerBand, windows.data.height - firstRow);
        const int firstY = dataWindow.min.y + int(firstRow), lastY = firstY + int(rows) - 1;
        // The slices' origin is the band's first row: `block` holds the band alone.
        const Imath::Box2i band(Imath::V2i(dataWindow.min.x, firstY), Imath::V2i(dataWindow.max.x, lastY));
        Imf::FrameBuffer frameBuffer;
        for (std::size_t slot = 0; slot < distinct.size(); ++slot) {
          const std::string& name = channelNames_[std::size_t(image)].at(std::size_t(distinct[slot]));
          const Imf::Channel& channel = header.channels()[name];
          if (channel.xSampling != 1 || channel.ySampling != 1)
            fail(path_, "channel " + name + " is subsampled, which is not supported");
          frameBuffer.insert(name, Imf::Slice::Make(Imf::FLOAT, block.data() + slot, band, pixelStride,
                                                    pixelStride * std::size_t(windows.data.width)));
        }
        part.setFrameBuffer(frameBuffer);
        part.readPixels(firstY, lastY);
        place(block.data(), firstRow, rows);
      }
    } catch (const Error&) {
      throw;
    } catch (const std::exception& error) {
      fail(path_, "cannot read pixels: " + oneLine(error.what()));
    }
    return images;
  }

 private:
  std::filesystem::path path_;
  std::uint64_t decodeBandBytes_;
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

std::unique_ptr<ImageReader> openExrImage(const std::filesystem::path& path, std::uint64_t decodeBandBytes) {
  return std::make_unique<ExrReader>(path, decodeBandBytes);
}

}  // namespace spindrift
