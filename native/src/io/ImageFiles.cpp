#include "io/ImageFiles.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "io/ExrHeaderCheck.h"
#include "io/ImageFileErrors.h"
#include "io/ImageReader.h"
#include "io/ImageWindows.h"
#include "io/JpegMarkerCheck.h"
#include "io/PngChunkCheck.h"
#include "spindrift/Error.h"
#include "spindrift/Limits.h"

namespace spindrift {
namespace {

using image_file_errors::fail;

std::unique_ptr<ImageReader> openImage(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) fail(path, "no such image file");
  checkExrHeaderClaims(path);
  if (isExrFile(path)) return openExrImage(path);
  checkPngChunkClaims(path);
  checkJpegMarkerClaims(path);
  return openOtherImage(path);
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

using ChannelNames = std::vector<std::string>;

int channelIndex(const ChannelNames& names, const std::string& name) {
  const auto found = std::find(names.begin(), names.end(), name);
  return found == names.end() ? -1 : int(found - names.begin());
}

// Channel indices of R, G, B, A within one layer (`prefix` is "" or "Layer."); A may be -1.
bool findRgba(const ChannelNames& spec, const std::string& prefix, std::array<int, 4>* rgba) {
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
bool findColorChannels(const ChannelNames& spec, std::array<int, 4>* rgba) {
  for (const std::string& name : spec) {
    const std::string layer = layerOf(name);
    if (layer.find("Combined") != std::string::npos && findRgba(spec, layer + ".", rgba)) return true;
  }
  if (findRgba(spec, "", rgba)) return true;
  int grey = channelIndex(spec, "Y");
  if (grey < 0 && spec.size() == 1 && !isDepthChannel(spec[0])) grey = 0;
  if (grey < 0) return false;
  *rgba = {grey, grey, grey, channelIndex(spec, "A")};
  return true;
}

float linearFromSrgb(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// Brings colour stored in a display encoding to linear, and unassociated alpha to premultiplied, so every
// colour image comes back as Blender's Combined pass is: linear and premultiplied.
void toLinearPremultiplied(const ColorEncoding& encoding, FloatImage* rgba) {
  if (!encoding.srgb && encoding.gamma == 1.0f && !encoding.unassociatedAlpha) return;
  for (std::size_t pixel = 0; pixel < rgba->pixels.size(); pixel += 4) {
    float* value = &rgba->pixels[pixel];
    for (int c = 0; c < 3; ++c) {
      if (encoding.srgb) value[c] = linearFromSrgb(value[c]);
      if (encoding.gamma != 1.0f) value[c] = std::pow(std::max(value[c], 0.0f), encoding.gamma);
      if (encoding.unassociatedAlpha) value[c] *= value[3];
    }
  }
}

}  // namespace

FloatImage readColorImage(const std::filesystem::path& path) {
  std::unique_ptr<ImageReader> input = openImage(path);
  for (int subimage = 0; subimage < input->imageCount(); ++subimage) {
    std::array<int, 4> rgba;
    if (!findColorChannels(input->channelNames(subimage), &rgba)) continue;
    FloatImage image = input->readChannels(subimage, {rgba.begin(), rgba.end()}, 1.0f);
    toLinearPremultiplied(input->colorEncoding(subimage), &image);
    return image;
  }
  fail(path, "no colour channels (looked for a *Combined* layer, R G B, or grey)");
}

std::optional<FloatImage> readDepthImage(const std::filesystem::path& path) {
  std::unique_ptr<ImageReader> input = openImage(path);
  for (int subimage = 0; subimage < input->imageCount(); ++subimage) {
    const ChannelNames& names = input->channelNames(subimage);
    const auto depth = std::find_if(names.begin(), names.end(), isDepthChannel);
    if (depth == names.end()) continue;
    return input->readChannels(subimage, {int(depth - names.begin())}, 0.0f);
  }
  return std::nullopt;
}

std::optional<std::array<FloatImage, 3>> readLightPasses(const std::filesystem::path& path) {
  std::unique_ptr<ImageReader> input = openImage(path);
  const char* passNames[6] = {"DiffDir", "DiffInd", "DiffCol", "GlossDir", "GlossInd", "GlossCol"};
  for (int subimage = 0; subimage < input->imageCount(); ++subimage) {
    const ChannelNames& spec = input->channelNames(subimage);
    std::array<FloatImage, 6> passes;
    bool complete = true;
    for (int pass = 0; pass < 6 && complete; ++pass) {
      std::array<int, 4> rgba{-1, -1, -1, -1};
      complete = false;
      for (const std::string& name : spec) {
        const std::string layer = layerOf(name);
        const std::string suffix = passNames[pass];
        if (layer.size() >= suffix.size() &&
            layer.compare(layer.size() - suffix.size(), suffix.size(), suffix) == 0 &&
            findRgba(spec, layer + ".", &rgba)) {
          complete = true;
          break;
        }
      }
      if (complete) passes[pass] = input->readChannels(subimage, {rgba[0], rgba[1], rgba[2], -1}, 0.0f);
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
  if (width <= 0 || height <= 0 || (long long)width * height > kMaxImagePixels) {
    throw Error("resizeImage: cannot resize to " + std::to_string(width) + "x" + std::to_string(height));
  }
  if (width == image.width && height == image.height) return image;
  requireMemory(std::uint64_t(width) * std::uint64_t(height) * std::uint64_t(image.channels) * sizeof(float),
                "resizing an image to " + std::to_string(width) + "x" + std::to_string(height));

  // One sample per destination pixel centre, as OpenImageIO's resample() takes it: bilinear between the four
  // nearest source pixels (edges repeated), or for `nearest` the source pixel the centre falls in, which
  // keeps depth discontinuities from blending into phantom surfaces.
  FloatImage result;
  result.width = width;
  result.height = height;
  result.channels = image.channels;
  result.pixels.resize(std::size_t(width) * height * image.channels);
  const auto clampedPixel = [&](int x, int y) {
    x = std::clamp(x, 0, image.width - 1);
    y = std::clamp(y, 0, image.height - 1);
    return &image.pixels[(std::size_t(y) * image.width + x) * image.channels];
  };
  for (int y = 0; y < height; ++y) {
    const float sourceY = (float(y) + 0.5f) / float(height) * float(image.height);
    for (int x = 0; x < width; ++x) {
      const float sourceX = (float(x) + 0.5f) / float(width) * float(image.width);
      float* target = &result.pixels[(std::size_t(y) * width + x) * image.channels];
      if (nearest) {
        const float* source = clampedPixel(int(std::floor(sourceX)), int(std::floor(sourceY)));
        std::copy(source, source + image.channels, target);
        continue;
      }
      const float left = std::floor(sourceX - 0.5f), top = std::floor(sourceY - 0.5f);
      const float s = sourceX - 0.5f - left, t = sourceY - 0.5f - top;
      const float* p00 = clampedPixel(int(left), int(top));
      const float* p10 = clampedPixel(int(left) + 1, int(top));
      const float* p01 = clampedPixel(int(left), int(top) + 1);
      const float* p11 = clampedPixel(int(left) + 1, int(top) + 1);
      for (int c = 0; c < image.channels; ++c) {
        const float upper = (1.0f - s) * p00[c] + s * p10[c];
        const float lower = (1.0f - s) * p01[c] + s * p11[c];
        target[c] = (1.0f - t) * upper + t * lower;
      }
    }
  }
  return result;
}

}  // namespace spindrift
