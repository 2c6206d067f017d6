#include "io/ImageFiles.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include "io/ExrHeaderCheck.h"
#include "io/JpegMarkerCheck.h"
#include "io/OiioErrors.h"
#include "io/PngChunkCheck.h"
#include "spindrift/Error.h"
#include "spindrift/Limits.h"

namespace spindrift {
namespace {

// Larger images are certainly a corrupt header, and refusing them keeps a bad file from becoming an
// allocation failure instead of an Error.
constexpr long long kMaxPixels = 1LL << 30;

using oiio_errors::fail;
using oiio_errors::oneLine;

std::unique_ptr<OIIO::ImageInput> openImage(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) fail(path, "no such image file");
  checkExrHeaderClaims(path);
  checkPngChunkClaims(path);
  checkJpegMarkerClaims(path);
  // Keep unassociated alpha (PNG, TIFF) as stored: OIIO would otherwise premultiply the sRGB-encoded
  // values, and premultiplying is only right after decoding to linear.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path.string(), &config);
  if (!input) fail(path, "cannot read image: " + oneLine(OIIO::geterror()));
  return input;
}

// "ViewLayer.Combined.R" is layer "ViewLayer.Combined", channel "R"; "R" is layer "", channel "R".
std::string layerOf(const std::string& channelName) {
  const std::size_t dot = channelName.rfind('.');
  return dot == std::string::npos ? std::string() : channelName.substr(0, dot);
}

std::string channelOf(const std::string& channelName) {
  const std::size_t dot = channelName.rfind('.');
  return dot == std::string::npos ? channelName : channelName.substr(dot + 1);
}

int channelIndex(const OIIO::ImageSpec& spec, const std::string& name) {
  const auto found = std::find(spec.channelnames.begin(), spec.channelnames.end(), name);
  return found == spec.channelnames.end() ? -1 : int(found - spec.channelnames.begin());
}

// Channel indices of R, G, B, A within one layer (`prefix` is "" or "Layer."); A may be -1.
bool findRgba(const OIIO::ImageSpec& spec, const std::string& prefix, std::array<int, 4>* rgba) {
  *rgba = {channelIndex(spec, prefix + "R"), channelIndex(spec, prefix + "G"),
           channelIndex(spec, prefix + "B"), channelIndex(spec, prefix + "A")};
  return (*rgba)[0] >= 0 && (*rgba)[1] >= 0 && (*rgba)[2] >= 0;
}

bool isDepthChannel(const std::string& channelName) {
  if (channelName == "Z") return true;
  const std::string layer = layerOf(channelName);
  return channelOf(channelName) == "Z" &&
         (layer.find("Depth") != std::string::npos || layer.find("depth") != std::string::npos);
}

// The colour channels of one subimage as R, G, B, A indices (alpha -1 when absent), or false when it has
// none. Blender's Combined layer comes first, then plain RGB, then grey.
bool findColorChannels(const OIIO::ImageSpec& spec, std::array<int, 4>* rgba) {
  for (const std::string& name : spec.channelnames) {
    const std::string layer = layerOf(name);
    if (layer.find("Combined") != std::string::npos && findRgba(spec, layer + ".", rgba)) return true;
  }
  if (findRgba(spec, "", rgba)) return true;
  int grey = channelIndex(spec, "Y");
  if (grey < 0 && spec.nchannels == 1 && !isDepthChannel(spec.channelnames[0])) grey = 0;
  if (grey < 0) return false;
  *rgba = {grey, grey, grey, channelIndex(spec, "A")};
  return true;
}

// Reads the listed channels of the current subimage as interleaved floats (a channel index of -1 gives
// `missingValue`), over the display window, top row first. Pixels outside the data window are 0.
FloatImage readChannels(OIIO::ImageInput& input, const std::filesystem::path& path, int subimage,
                        const std::vector<int>& channels, float missingValue) {
  const OIIO::ImageSpec spec = input.spec();
  if (spec.deep) fail(path, "deep images are not supported");
  const bool hasDisplayWindow = spec.full_width > 0 && spec.full_height > 0;
  const int originX = hasDisplayWindow ? spec.full_x : spec.x;
  const int originY = hasDisplayWindow ? spec.full_y : spec.y;
  FloatImage image;
  image.width = hasDisplayWindow ? spec.full_width : spec.width;
  image.height = hasDisplayWindow ? spec.full_height : spec.height;
  image.channels = int(channels.size());
  if (spec.width <= 0 || spec.height <= 0 || image.width <= 0 || image.height <= 0 ||
      (long long)spec.width * spec.height > kMaxPixels ||
      (long long)image.width * image.height > kMaxPixels) {
    fail(path, "unsupported image size " + std::to_string(spec.width) + "x" + std::to_string(spec.height));
  }

  int firstChannel = spec.nchannels;
  int lastChannel = -1;
  for (int channel : channels) {
    if (channel < 0) continue;
    firstChannel = std::min(firstChannel, channel);
    lastChannel = std::max(lastChannel, channel);
  }
  const int blockChannels = std::max(0, lastChannel + 1 - firstChannel);
  // OpenImageIO 2.4 converts a scanline image through a buffer of a chunk of rows, about 256 of them however
  // few the image has (fuzz_background_image: a 4,259,848 x 6 EXR made it allocate 13 GB, 3,072 bytes a
  // column for three float channels), so that buffer counts too, at the file's channels and 4 bytes each.
  constexpr std::uint64_t kConversionRows = 256;
  requireMemory(
      (std::uint64_t(spec.width) * std::uint64_t(spec.height) * std::uint64_t(blockChannels) +
       std::uint64_t(image.width) * std::uint64_t(image.height) * std::uint64_t(image.channels) +
       std::uint64_t(spec.width) * kConversionRows * std::uint64_t(std::max(blockChannels, spec.nchannels))) *
          sizeof(float),
      path.string() + ": a " + std::to_string(image.width) + "x" + std::to_string(image.height) + " image");
  std::vector<float> block(std::size_t(spec.width) * spec.height * blockChannels);
  if (blockChannels > 0 &&
      !input.read_image(subimage, 0, firstChannel, lastChannel + 1, OIIO::TypeFloat, block.data())) {
    fail(path, "cannot read pixels: " + oneLine(input.geterror()));
  }

  image.pixels.assign(std::size_t(image.width) * image.height * image.channels, 0.0f);
  for (int dataY = 0; dataY < spec.height; ++dataY) {
    const int y = spec.y + dataY - originY;
    if (y < 0 || y >= image.height) continue;
    for (int dataX = 0; dataX < spec.width; ++dataX) {
      const int x = spec.x + dataX - originX;
      if (x < 0 || x >= image.width) continue;
      const float* source = &block[(std::size_t(dataY) * spec.width + dataX) * blockChannels];
      float* target = &image.pixels[(std::size_t(y) * image.width + x) * image.channels];
      for (int c = 0; c < image.channels; ++c) {
        target[c] = channels[c] < 0 ? missingValue : source[channels[c] - firstChannel];
      }
    }
  }
  return image;
}

float linearFromSrgb(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// Brings colour stored in a display encoding to linear, and unassociated alpha to premultiplied, so every
// colour image comes back as Blender's Combined pass is: linear and premultiplied.
void toLinearPremultiplied(const OIIO::ImageSpec& spec, FloatImage* rgba) {
  const std::string colorSpace = spec.get_string_attribute("oiio:ColorSpace");
  const bool isSrgb = OIIO::Strutil::iequals(colorSpace, "sRGB");
  const float gamma =
      OIIO::Strutil::istarts_with(colorSpace, "Gamma") ? spec.get_float_attribute("oiio:Gamma", 1) : 1.0f;
  const bool unassociatedAlpha = spec.get_int_attribute("oiio:UnassociatedAlpha", 0) != 0;
  for (std::size_t pixel = 0; pixel < rgba->pixels.size(); pixel += 4) {
    float* value = &rgba->pixels[pixel];
    for (int c = 0; c < 3; ++c) {
      if (isSrgb) value[c] = linearFromSrgb(value[c]);
      if (gamma != 1.0f) value[c] = std::pow(std::max(value[c], 0.0f), gamma);
      if (unassociatedAlpha) value[c] *= value[3];
    }
  }
}

}  // namespace

FloatImage readColorImage(const std::filesystem::path& path) {
  std::unique_ptr<OIIO::ImageInput> input = openImage(path);
  for (int subimage = 0; input->seek_subimage(subimage, 0); ++subimage) {
    std::array<int, 4> rgba;
    if (!findColorChannels(input->spec(), &rgba)) continue;
    FloatImage image = readChannels(*input, path, subimage, {rgba.begin(), rgba.end()}, 1.0f);
    toLinearPremultiplied(input->spec(), &image);
    return image;
  }
  fail(path, "no colour channels (looked for a *Combined* layer, R G B, or grey)");
}

std::optional<FloatImage> readDepthImage(const std::filesystem::path& path) {
  std::unique_ptr<OIIO::ImageInput> input = openImage(path);
  for (int subimage = 0; input->seek_subimage(subimage, 0); ++subimage) {
    const std::vector<std::string>& names = input->spec().channelnames;
    const auto depth = std::find_if(names.begin(), names.end(), isDepthChannel);
    if (depth == names.end()) continue;
    return readChannels(*input, path, subimage, {int(depth - names.begin())}, 0.0f);
  }
  return std::nullopt;
}

std::optional<std::array<FloatImage, 3>> readLightPasses(const std::filesystem::path& path) {
  std::unique_ptr<OIIO::ImageInput> input = openImage(path);
  const char* passNames[6] = {"DiffDir", "DiffInd", "DiffCol", "GlossDir", "GlossInd", "GlossCol"};
  for (int subimage = 0; input->seek_subimage(subimage, 0); ++subimage) {
    const OIIO::ImageSpec& spec = input->spec();
    std::array<FloatImage, 6> passes;
    bool complete = true;
    for (int pass = 0; pass < 6 && complete; ++pass) {
      std::array<int, 4> rgba{-1, -1, -1, -1};
      complete = false;
      for (const std::string& name : spec.channelnames) {
        const std::string layer = layerOf(name);
        const std::string suffix = passNames[pass];
        if (layer.size() >= suffix.size() &&
            layer.compare(layer.size() - suffix.size(), suffix.size(), suffix) == 0 &&
            findRgba(spec, layer + ".", &rgba)) {
          complete = true;
          break;
        }
      }
      if (complete)
        passes[pass] = readChannels(*input, path, subimage, {rgba[0], rgba[1], rgba[2], -1}, 0.0f);
    }
    if (!complete) continue;
    std::array<FloatImage, 3> light{passes[0], passes[3], passes[1]};
    for (std::size_t i = 0; i < light[0].pixels.size(); ++i) {
      if (i % 4 == 3) {
        // DiffDir alone (its mean over R, G, B): the light that the lamps' share is measured against.
        light[0].pixels[i] =
            (passes[0].pixels[i - 3] + passes[0].pixels[i - 2] + passes[0].pixels[i - 1]) / 3.0f;
        continue;
      }
      light[0].pixels[i] = passes[2].pixels[i] * passes[0].pixels[i];
      light[1].pixels[i] = passes[5].pixels[i] * passes[3].pixels[i];
      light[2].pixels[i] =
          passes[2].pixels[i] * passes[1].pixels[i] + passes[5].pixels[i] * passes[4].pixels[i];
    }
    return light;
  }
  return std::nullopt;
}

FloatImage resizeImage(const FloatImage& image, int width, int height, bool nearest) {
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0 ||
      image.pixels.size() != std::size_t(image.width) * image.height * image.channels) {
    throw Error("resizeImage: the source image is empty or its pixel count does not match its size");
  }
  if (width <= 0 || height <= 0 || (long long)width * height > kMaxPixels) {
    throw Error("resizeImage: cannot resize to " + std::to_string(width) + "x" + std::to_string(height));
  }
  if (width == image.width && height == image.height) return image;
  // The copy into OIIO, its result and ours: three images of the larger size at most.
  requireMemory(
      3 * std::uint64_t(std::max(width * (long long)height, image.width * (long long)image.height)) *
          std::uint64_t(image.channels) * sizeof(float),
      "resizing an image to " + std::to_string(width) + "x" + std::to_string(height));

  OIIO::ImageBuf source(OIIO::ImageSpec(image.width, image.height, image.channels, OIIO::TypeFloat));
  source.set_pixels(OIIO::ROI::All(), OIIO::TypeFloat, image.pixels.data());
  OIIO::ImageBuf resized(OIIO::ImageSpec(width, height, image.channels, OIIO::TypeFloat));
  // resample() takes one sample per destination pixel centre: bilinear with `interpolate`, else the
  // nearest source pixel, which keeps depth discontinuities from blending into phantom surfaces.
  if (!OIIO::ImageBufAlgo::resample(resized, source, /*interpolate=*/!nearest)) {
    throw Error("resizeImage: " + oneLine(resized.geterror()));
  }
  FloatImage result;
  result.width = width;
  result.height = height;
  result.channels = image.channels;
  result.pixels.resize(std::size_t(width) * height * image.channels);
  resized.get_pixels(OIIO::ROI::All(), OIIO::TypeFloat, result.pixels.data());
  return result;
}

}  // namespace spindrift
