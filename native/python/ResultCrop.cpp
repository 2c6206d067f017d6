#include "ResultCrop.h"

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "spindrift/Error.h"

namespace spindrift::python {
namespace {

void remapRefractionUv(ImageLayer& layer, int fullWidth, int fullHeight, const CropWindow& window) {
  if (layer.channelCount() < 3) return;
  const std::size_t channels = layer.channelCount();
  // The window's bottom edge, counted in rows from the full image's bottom (v's origin).
  const float bottom = float(fullHeight - window.y - window.height);
  const float uMin = 0.5f / float(window.width), uMax = 1.0f - uMin;
  const float vMin = 0.5f / float(window.height), vMax = 1.0f - vMin;
  for (std::size_t pixel = 0; pixel < layer.pixels.size() / channels; ++pixel) {
    float* uv = &layer.pixels[pixel * channels];
    if (uv[2] <= 0.0f) continue;  // Not a pixel whose ray reads the background: u, v mean nothing there.
    uv[0] = std::clamp((uv[0] * float(fullWidth) - float(window.x)) / float(window.width), uMin, uMax);
    uv[1] = std::clamp((uv[1] * float(fullHeight) - bottom) / float(window.height), vMin, vMax);
  }
}

}  // namespace

void cropResult(RenderResult& result, const CropWindow& window) {
  if (window.x < 0 || window.y < 0 || window.width < 1 || window.height < 1 ||
      window.x + window.width > result.width || window.y + window.height > result.height)
    throw Error("crop " + std::to_string(window.width) + "x" + std::to_string(window.height) + " at (" +
                std::to_string(window.x) + ", " + std::to_string(window.y) + ") does not lie inside the " +
                std::to_string(result.width) + "x" + std::to_string(result.height) + " image");
  for (ImageLayer& layer : result.layers) {
    const std::size_t channels = layer.channelCount();
    std::vector<float> cropped(std::size_t(window.width) * std::size_t(window.height) * channels);
    for (int row = 0; row < window.height; ++row) {
      const std::size_t from =
          (std::size_t(window.y + row) * std::size_t(result.width) + std::size_t(window.x));
      std::copy_n(&layer.pixels[from * channels], std::size_t(window.width) * channels,
                  &cropped[std::size_t(row) * std::size_t(window.width) * channels]);
    }
    layer.pixels = std::move(cropped);
    if (layer.name == "refraction_uv") remapRefractionUv(layer, result.width, result.height, window);
  }
  result.width = window.width;
  result.height = window.height;
}

}  // namespace spindrift::python
