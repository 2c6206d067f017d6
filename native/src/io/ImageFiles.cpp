#include "io/ImageFiles.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
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

// Sets of channels asked of one open file, read image by image with one readChannelSets call each, so
// that an OpenEXR part is decoded once however many of the readers below take channels from it.
class ChannelRequests {
 public:
  // The index of the set's image among read()'s results.
  std::size_t add(int image, ChannelSet set) {
    requests_.push_back({image, std::move(set)});
    return requests_.size() - 1;
  }

  std::vector<FloatImage> read(ImageReader& input) const {
    std::vector<FloatImage> images(requests_.size());
    std::vector<bool> done(requests_.size(), false);
    for (std::size_t first = 0; first < requests_.size(); ++first) {
      if (done[first]) continue;
      std::vector<std::size_t> members;
      std::vector<ChannelSet> sets;
      for (std::size_t k = first; k < requests_.size(); ++k)
        if (!done[k] && requests_[k].image == requests_[first].image) {
          members.push_back(k);
          sets.push_back(requests_[k].set);
          done[k] = true;
        }
      std::vector<FloatImage> read = input.readChannelSets(requests_[first].image, sets);
      for (std::size_t m = 0; m < members.size(); ++m)
        images[members[m]] = std::move(read[m]);
    }
    return images;
  }

 private:
  struct Request {
    int image;
    ChannelSet set;
  };
  std::vector<Request> requests_;
};

// The colour of the first subimage that has colour channels (alpha 1 where it has none).
struct ColorRequest {
  std::size_t set;
  ColorEncoding encoding;
};

std::optional<ColorRequest> requestColor(const ImageReader& input, ChannelRequests& requests) {
  for (int subimage = 0; subimage < input.imageCount(); ++subimage) {
    std::array<int, 4> rgba;
    if (!findColorChannels(input.channelNames(subimage), &rgba)) continue;
    return ColorRequest{requests.add(subimage, {{rgba.begin(), rgba.end()}, 1.0f}),
                        input.colorEncoding(subimage)};
  }
  return std::nullopt;
}

// The first depth channel of any subimage.
std::optional<std::size_t> requestDepth(const ImageReader& input, ChannelRequests& requests) {
  for (int subimage = 0; subimage < input.imageCount(); ++subimage) {
    const ChannelNames& names = input.channelNames(subimage);
    const auto depth = std::find_if(names.begin(), names.end(), isDepthChannel);
    if (depth == names.end()) continue;
    return requests.add(subimage, {{int(depth - names.begin())}, 0.0f});
  }
  return std::nullopt;
}

// Cycles' six light passes, in this order, each as RGB with alpha 0, from the first subimage that has all
// six.
constexpr std::array<const char*, 6> kLightPassNames = {"DiffDir",  "DiffInd",  "DiffCol",
                                                        "GlossDir", "GlossInd", "GlossCol"};

std::optional<std::array<std::size_t, 6>> requestLightPasses(const ImageReader& input,
                                                             ChannelRequests& requests) {
  for (int subimage = 0; subimage < input.imageCount(); ++subimage) {
    const ChannelNames& spec = input.channelNames(subimage);
    std::array<std::array<int, 4>, 6> channels;
    bool complete = true;
    for (std::size_t pass = 0; pass < kLightPassNames.size() && complete; ++pass) {
      complete = false;
      const std::string suffix = kLightPassNames[pass];
      for (const std::string& name : spec) {
        const std::string layer = layerOf(name);
        if (layer.size() >= suffix.size() &&
            layer.compare(layer.size() - suffix.size(), suffix.size(), suffix) == 0 &&
            findRgba(spec, layer + ".", &channels[pass])) {
          complete = true;
          break;
        }
      }
    }
    if (!complete) continue;
    std::array<std::size_t, 6> sets;
    for (std::size_t pass = 0; pass < sets.size(); ++pass)
      sets[pass] =
          requests.add(subimage, {{channels[pass][0], channels[pass][1], channels[pass][2], -1}, 0.0f});
    return sets;
  }
  return std::nullopt;
}

// Direct diffuse (DiffCol x DiffDir, alpha DiffDir's mean), direct glossy and indirect light from the six.
std::array<FloatImage, 3> combineLightPasses(const std::vector<FloatImage>& images,
                                             const std::array<std::size_t, 6>& sets) {
  const FloatImage& diffDir = images[sets[0]];
  const FloatImage& diffInd = images[sets[1]];
  const FloatImage& diffCol = images[sets[2]];
  const FloatImage& glossDir = images[sets[3]];
  const FloatImage& glossInd = images[sets[4]];
  const FloatImage& glossCol = images[sets[5]];
  std::array<FloatImage, 3> light{diffDir, glossDir, diffInd};
  for (std::size_t i = 0; i < light[0].pixels.size(); ++i) {
    if (i % 4 == 3) {
      // DiffDir alone (its mean over R, G, B): the light that the lamps' share is measured against.
      light[0].pixels[i] = (diffDir.pixels[i - 3] + diffDir.pixels[i - 2] + diffDir.pixels[i - 1]) / 3.0f;
      continue;
    }
    light[0].pixels[i] = diffCol.pixels[i] * diffDir.pixels[i];
    light[1].pixels[i] = glossCol.pixels[i] * glossDir.pixels[i];
    light[2].pixels[i] = diffCol.pixels[i] * diffInd.pixels[i] + glossCol.pixels[i] * glossInd.pixels[i];
  }
  return light;
}

[[noreturn]] void failWithoutColor(const std::filesystem::path& path) {
  fail(path, "no colour channels (looked for a *Combined* layer, R G B, or grey)");
}

}  // namespace

FloatImage readColorImage(const std::filesystem::path& path) {
  std::unique_ptr<ImageReader> input = openImage(path);
  ChannelRequests requests;
  const std::optional<ColorRequest> color = requestColor(*input, requests);
  if (!color) failWithoutColor(path);
  FloatImage image = std::move(requests.read(*input)[color->set]);
  toLinearPremultiplied(color->encoding, &image);
  return image;
}

std::optional<FloatImage> readDepthImage(const std::filesystem::path& path) {
  std::unique_ptr<ImageReader> input = openImage(path);
  ChannelRequests requests;
  const std::optional<std::size_t> depth = requestDepth(*input, requests);
  if (!depth) return std::nullopt;
  return std::move(requests.read(*input)[*depth]);
}

BackgroundFile readBackgroundFile(const std::filesystem::path& path, bool withDepth) {
  return readBackgroundFile(*openImage(path), path, withDepth);
}

BackgroundFile readBackgroundFile(ImageReader& input, const std::filesystem::path& path, bool withDepth) {
  ChannelRequests requests;
  const std::optional<ColorRequest> color = requestColor(input, requests);
  if (!color) failWithoutColor(path);
  const std::optional<std::size_t> depth = withDepth ? requestDepth(input, requests) : std::nullopt;
  const std::optional<std::array<std::size_t, 6>> passes = requestLightPasses(input, requests);
  std::vector<FloatImage> images = requests.read(input);
  BackgroundFile file;
  file.color = std::move(images[color->set]);
  toLinearPremultiplied(color->encoding, &file.color);
  if (depth) file.depth = std::move(images[*depth]);
  if (passes) file.lightPasses = combineLightPasses(images, *passes);
  return file;
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
