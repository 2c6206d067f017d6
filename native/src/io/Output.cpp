#include "spindrift/Output.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <png.h>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include "io/ExrThreads.h"
#include "io/ImageFileErrors.h"
#include "spindrift/Error.h"

namespace spindrift {
namespace {

using image_file_errors::fail;
using image_file_errors::oneLine;

void checkLayerSizes(const RenderResult& result, const std::vector<const ImageLayer*>& layers,
                     const std::filesystem::path& path) {
  if (result.width <= 0 || result.height <= 0) {
    fail(path, "nothing to write: the image is " + std::to_string(result.width) + "x" +
                   std::to_string(result.height));
  }
  const std::size_t pixelCount = std::size_t(result.width) * std::size_t(result.height);
  for (const ImageLayer* layerPointer : layers) {
    const ImageLayer& layer = *layerPointer;
    if (layer.channels.empty() || layer.pixels.size() != pixelCount * layer.channelCount()) {
      fail(path, "layer '" + layer.name + "' has " + std::to_string(layer.pixels.size()) +
                     " values, expected " + std::to_string(pixelCount) + " pixels of " +
                     std::to_string(layer.channelCount()) + " channels");
    }
  }
}

// A name beside the target, hidden, and unique per process and call, so concurrent writers never share it.
std::filesystem::path temporaryPathBeside(const std::filesystem::path& target) {
  static std::atomic<unsigned> callCounter{0};
  const std::string suffix = ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(callCounter++);
  return target.parent_path() / ("." + target.filename().string() + suffix);
}

// Removes the temporary file unless the write got as far as renaming it, whatever goes wrong in between.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::filesystem::path path) : path_(std::move(path)) {}
  ~TemporaryFile() {
    if (!path_.empty()) {
      std::error_code ignored;
      std::filesystem::remove(path_, ignored);
    }
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  const std::filesystem::path& path() const { return path_; }
  void release() { path_.clear(); }

 private:
  std::filesystem::path path_;
};

// Writes the file under a temporary name beside `target` with `write`, then renames it into place, so
// `target` is either the old file or the complete new one. `write` throws on failure.
void writeThroughTemporaryFile(const std::filesystem::path& target,
                               const std::function<void(const std::filesystem::path&)>& write) {
  const std::filesystem::path directory = target.parent_path();
  if (!directory.empty()) {
    std::error_code directoryError;
    std::filesystem::create_directories(directory, directoryError);
    if (directoryError) {
      fail(target, "cannot create directory " + directory.string() + ": " + directoryError.message());
    }
  }
  TemporaryFile temporary(temporaryPathBeside(target));
  try {
    write(temporary.path());
  } catch (const Error&) {
    throw;
  } catch (const std::exception& error) {
    fail(target, "cannot write: " + oneLine(error.what()));
  }
  std::error_code renameError;
  std::filesystem::rename(temporary.path(), target, renameError);
  if (renameError) fail(target, "cannot replace the file: " + renameError.message());
  temporary.release();
}

float srgbFromLinear(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t quantize(float value) {
  if (std::isnan(value)) return 0;
  return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f));
}

int channelIndex(const ImageLayer& layer, const std::string& channel) {
  const auto found = std::find(layer.channels.begin(), layer.channels.end(), channel);
  return found == layer.channels.end() ? -1 : int(found - layer.channels.begin());
}

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// OpenEXR's compressions by the names OpenImageIO gave them, which the command line and the module take.
const std::map<std::string, Imf::Compression>& exrCompressionsByName() {
  static const std::map<std::string, Imf::Compression> byName = {
      {"none", Imf::NO_COMPRESSION},   {"rle", Imf::RLE_COMPRESSION},   {"zip", Imf::ZIP_COMPRESSION},
      {"zips", Imf::ZIPS_COMPRESSION}, {"piz", Imf::PIZ_COMPRESSION},   {"pxr24", Imf::PXR24_COMPRESSION},
      {"b44", Imf::B44_COMPRESSION},   {"b44a", Imf::B44A_COMPRESSION}, {"dwaa", Imf::DWAA_COMPRESSION},
      {"dwab", Imf::DWAB_COMPRESSION}};
  return byName;
}

// "zip:1" as OpenEXR's compression and zlib level (-1: OpenEXR's default level); checked valid first.
std::pair<Imf::Compression, int> exrCompression(const std::string& compression) {
  const std::size_t colon = compression.find(':');
  const int level = colon == std::string::npos ? -1 : std::stoi(compression.substr(colon + 1));
  return {exrCompressionsByName().at(compression.substr(0, colon)), level};
}

// One channel of a layer as writeExr stores it. OpenEXR writes a channel only from a slice of its own type:
// a float channel is written straight from its layer, a half one from `halves`, converted a chunk of rows
// at a time.
struct ExrChannel {
  std::string name;
  const float* source;  // the layer's first value of this channel
  std::size_t stride;   // the layer's channel count
  bool half;
  std::vector<Imath::half> halves;
};

// Rows per chunk of converted halves: a multiple of every OpenEXR compression's block (1, 16 or 32
// scanlines), and buffers small enough to be reused warm (converting the whole image at once allocated tens
// of MB per frame, and first touching those pages cost more than compressing them; docs/blender.md,
// "Per-final-frame overhead").
constexpr int kRowsPerChunk = 64;

void writeExrRows(Imf::OutputFile& file, std::vector<ExrChannel>& channels, int width, int height) {
  const std::size_t rowFloats = std::size_t(width);
  for (int firstRow = 0; firstRow < height; firstRow += kRowsPerChunk) {
    const int rows = std::min(height - firstRow, kRowsPerChunk);
    Imf::FrameBuffer frameBuffer;
    for (ExrChannel& channel : channels) {
      const std::size_t floatBytes = channel.stride * sizeof(float);
      if (!channel.half) {
        frameBuffer.insert(channel.name, Imf::Slice::Make(Imf::FLOAT, channel.source, Imath::V2i(0, 0), width,
                                                          height, floatBytes, floatBytes * rowFloats));
        continue;
      }
      channel.halves.resize(rowFloats * std::size_t(kRowsPerChunk));
      const float* source = channel.source + std::size_t(firstRow) * rowFloats * channel.stride;
      for (std::size_t i = 0; i < rowFloats * std::size_t(rows); ++i)
        channel.halves[i] = Imath::half(source[i * channel.stride]);
      frameBuffer.insert(channel.name,
                         Imf::Slice::Make(Imf::HALF, channel.halves.data(), Imath::V2i(0, firstRow), width,
                                          rows, sizeof(Imath::half), sizeof(Imath::half) * rowFloats));
    }
    file.setFrameBuffer(frameBuffer);
    file.writePixels(rows);
  }
}

}  // namespace

// A misspelt name or level is refused rather than guessed at: OpenImageIO, which once wrote these files,
// fell back to ZIP, or to its default level, without a word.
bool exrCompressionIsValid(const std::string& compression) {
  const std::size_t colon = compression.find(':');
  const std::string name = compression.substr(0, colon);
  if (exrCompressionsByName().count(name) == 0) return false;
  if (colon == std::string::npos) return true;
  const std::string level = compression.substr(colon + 1);
  return (name == "zip" || name == "zips") && level.size() == 1 && level[0] >= '1' && level[0] <= '9';
}

bool exrLayerNeedsFloat(const std::string& layerName) {
  return layerName == "depth" || layerName == "refraction_uv" || endsWith(layerName, "_depth");
}

void writeExr(const RenderResult& result, const std::filesystem::path& path, const ExrOptions& options) {
  std::vector<const ImageLayer*> layers;
  for (const ImageLayer& layer : result.layers)
    if (options.layers.empty() ||
        std::find(options.layers.begin(), options.layers.end(), layer.name) != options.layers.end())
      layers.push_back(&layer);
  checkLayerSizes(result, layers, path);
  if (layers.empty()) fail(path, "nothing to write: the result has no layers");

  std::vector<std::string> channelNames;
  for (const ImageLayer* layer : layers) {
    for (const std::string& channel : layer->channels) {
      channelNames.push_back(layer->name.empty() ? channel : layer->name + "." + channel);
    }
  }
  const std::set<std::string> uniqueNames(channelNames.begin(), channelNames.end());
  if (uniqueNames.size() != channelNames.size()) fail(path, "two layers have a channel of the same name");

  if (!exrCompressionIsValid(options.compression))
    fail(path, "unknown EXR compression \"" + options.compression + "\"");
  const auto [compression, level] = exrCompression(options.compression);
  Imf::Header header(result.width, result.height);
  header.compression() = compression;
  if (level > 0) header.zipCompressionLevel() = level;
  std::vector<ExrChannel> channels;
  std::size_t name = 0;
  for (const ImageLayer* layer : layers) {
    const bool half = options.halfColor && !exrLayerNeedsFloat(layer->name);
    for (std::size_t c = 0; c < layer->channelCount(); ++c, ++name) {
      header.channels().insert(channelNames[name], Imf::Channel(half ? Imf::HALF : Imf::FLOAT));
      channels.push_back({channelNames[name], layer->pixels.data() + c, layer->channelCount(), half, {}});
    }
  }
  // No time stamp or host name goes into the header: the same frame gives the same file on every node and
  // every run, so farm output can be checked byte for byte.
  useEveryCoreForOpenExrUnlessTheHostChose();
  writeThroughTemporaryFile(path, [&](const std::filesystem::path& temporary) {
    Imf::OutputFile file(temporary.c_str(), header);
    writeExrRows(file, channels, result.width, result.height);
  });
}

void writePng(const RenderResult& result, const std::filesystem::path& path) {
  const auto composite = std::find_if(result.layers.begin(), result.layers.end(),
                                      [](const ImageLayer& layer) { return layer.name == "composite"; });
  if (composite == result.layers.end()) fail(path, "cannot write a PNG: the result has no composite layer");
  std::vector<const ImageLayer*> everyLayer;
  for (const ImageLayer& layer : result.layers)
    everyLayer.push_back(&layer);
  checkLayerSizes(result, everyLayer, path);
  const int red = channelIndex(*composite, "R");
  const int green = channelIndex(*composite, "G");
  const int blue = channelIndex(*composite, "B");
  const int alpha = channelIndex(*composite, "A");
  if (red < 0 || green < 0 || blue < 0) fail(path, "the composite layer has no R, G and B channels");

  const std::size_t pixelCount = std::size_t(result.width) * std::size_t(result.height);
  const std::size_t sourceChannels = composite->channelCount();
  std::vector<std::uint8_t> encoded(pixelCount * 4);
  for (std::size_t pixel = 0; pixel < pixelCount; ++pixel) {
    const float* source = &composite->pixels[pixel * sourceChannels];
    const float opacity = alpha >= 0 ? source[alpha] : 1.0f;
    std::uint8_t* target = &encoded[pixel * 4];
    const int rgb[3] = {red, green, blue};
    for (int c = 0; c < 3; ++c) {
      // PNG stores straight alpha; where alpha is 0 there is no colour to recover and it stays as it is.
      const float straight = opacity > 0.0f ? source[rgb[c]] / opacity : source[rgb[c]];
      target[c] = quantize(srgbFromLinear(straight));
    }
    target[3] = quantize(opacity);
  }

  // libpng's simplified writer: 8-bit sRGB with straight alpha (the values above), no time stamp, so
  // identical frames are identical files.
  writeThroughTemporaryFile(path, [&](const std::filesystem::path& temporary) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = png_uint_32(result.width);
    image.height = png_uint_32(result.height);
    image.format = PNG_FORMAT_RGBA;
    if (!png_image_write_to_file(&image, temporary.c_str(), 0, encoded.data(), 0, nullptr))
      throw std::runtime_error(image.message);
  });
}

}  // namespace spindrift
