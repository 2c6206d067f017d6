#include "spindrift/Output.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>

#include "io/OiioErrors.h"
#include "spindrift/Error.h"

namespace spindrift {
namespace {

using oiio_errors::fail;
using oiio_errors::oneLine;

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

// Writes with the OIIO plugin `formatName` under a temporary name beside `target`, then renames it into
// place, so `target` is either the old file or the complete new one. The format is named rather than
// guessed from the extension because the temporary name has none.
void writeThroughTemporaryFile(const std::filesystem::path& target, const char* formatName,
                               const OIIO::ImageSpec& spec,
                               const std::function<bool(OIIO::ImageOutput&)>& writePixels) {
  const std::filesystem::path directory = target.parent_path();
  if (!directory.empty()) {
    std::error_code directoryError;
    std::filesystem::create_directories(directory, directoryError);
    if (directoryError) {
      fail(target, "cannot create directory " + directory.string() + ": " + directoryError.message());
    }
  }
  std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(formatName);
  if (!output) fail(target, std::string("no ") + formatName + " writer: " + oneLine(OIIO::geterror()));

  TemporaryFile temporary(temporaryPathBeside(target));
  const bool written =
      output->open(temporary.path().string(), spec) && writePixels(*output) && output->close();
  if (!written) {
    const std::string message = oneLine(output->geterror());
    output.reset();  // Closes the file before the temporary is removed.
    fail(target, "cannot write: " + message);
  }
  output.reset();
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

// Rows per call to the writer: a multiple of every OpenEXR compression's block (1, 16 or 32 scanlines), and a
// buffer small enough to be reused warm. Interleaving the whole image at once allocated tens of MB per frame,
// and first touching those pages cost more than compressing them (docs/blender.md, "Per-final-frame
// overhead").
constexpr int kRowsPerChunk = 64;

// Writes the layers' channels interleaved into one pixel, layer after layer, in the spec's channel formats
// (float or half), a chunk of rows at a time, so OpenImageIO writes them as they are instead of converting
// mixed formats itself.
bool writeInterleavedRows(OIIO::ImageOutput& output, const std::vector<const ImageLayer*>& layers,
                          const OIIO::ImageSpec& spec) {
  struct Channel {
    const float* source;
    std::size_t stride;  // The layer's channel count.
    bool half;
  };
  std::vector<Channel> channels;
  for (const ImageLayer* layer : layers)
    for (std::size_t c = 0; c < layer->channelCount(); ++c)
      channels.push_back({layer->pixels.data() + c, layer->channelCount(),
                          spec.channelformat(int(channels.size())) == OIIO::TypeHalf});
  const std::size_t width = std::size_t(spec.width);
  std::vector<std::uint8_t> chunk(width * kRowsPerChunk * spec.pixel_bytes(true));
  for (int firstRow = 0; firstRow < spec.height; firstRow += kRowsPerChunk) {
    const int endRow = std::min(spec.height, firstRow + kRowsPerChunk);
    std::uint8_t* target = chunk.data();
    for (std::size_t pixel = std::size_t(firstRow) * width; pixel < std::size_t(endRow) * width; ++pixel) {
      for (const Channel& channel : channels) {
        const float value = channel.source[pixel * channel.stride];
        if (channel.half) {
          const Imath::half stored(value);
          std::memcpy(target, &stored, sizeof(stored));
          target += sizeof(stored);
        } else {
          std::memcpy(target, &value, sizeof(value));
          target += sizeof(value);
        }
      }
    }
    if (!output.write_scanlines(firstRow, endRow, 0, OIIO::TypeUnknown, chunk.data())) return false;
  }
  return true;
}

}  // namespace

// A misspelt name would make OpenImageIO's writer fall back to ZIP silently, and a level it cannot parse to
// its default.
bool exrCompressionIsValid(const std::string& compression) {
  static const std::set<std::string> names = {"none",  "rle", "zip",  "zips", "piz",
                                              "pxr24", "b44", "b44a", "dwaa", "dwab"};
  const std::size_t colon = compression.find(':');
  const std::string name = compression.substr(0, colon);
  if (names.count(name) == 0) return false;
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
  OIIO::ImageSpec spec(result.width, result.height, int(channelNames.size()), OIIO::TypeFloat);
  spec.channelnames = channelNames;
  if (options.halfColor) {
    for (const ImageLayer* layer : layers)
      for (std::size_t c = 0; c < layer->channelCount(); ++c)
        spec.channelformats.push_back(exrLayerNeedsFloat(layer->name) ? OIIO::TypeFloat : OIIO::TypeHalf);
  }
  const auto indexOf = [&](const std::string& name) {
    const auto found = std::find(channelNames.begin(), channelNames.end(), name);
    return found == channelNames.end() ? -1 : int(found - channelNames.begin());
  };
  spec.alpha_channel = indexOf("composite.A");
  spec.z_channel = indexOf("depth.Z");
  spec.attribute("compression", options.compression);
  spec.attribute("oiio:ColorSpace", "Linear");
  // OpenImageIO stamps the current time into the header (capDate) unless DateTime is given: left empty, the
  // same frame gives the same file on every node and every run, so farm output can be checked byte for byte.
  spec.attribute("DateTime", "");
  writeThroughTemporaryFile(path, "openexr", spec, [&](OIIO::ImageOutput& output) {
    return writeInterleavedRows(output, layers, spec);
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

  OIIO::ImageSpec spec(result.width, result.height, 4, OIIO::TypeUInt8);
  spec.alpha_channel = 3;
  // The values are already straight alpha; without this OIIO would divide by alpha a second time.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  spec.attribute("oiio:ColorSpace", "sRGB");
  spec.attribute("DateTime", "");  // As in writeExr: no time stamp, identical frames are identical files.
  writeThroughTemporaryFile(path, "png", spec, [&](OIIO::ImageOutput& output) {
    return output.write_image(OIIO::TypeUInt8, encoded.data());
  });
}

}  // namespace spindrift
