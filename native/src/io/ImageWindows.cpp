#include "io/ImageWindows.h"

#include <string>

#include "io/ImageFileErrors.h"

namespace spindrift {
namespace {

constexpr long long kMaxSide = 1LL << 30;

bool isReasonable(const PixelWindow& window) {
  return window.width > 0 && window.height > 0 && window.width <= kMaxSide && window.height <= kMaxSide &&
         window.width * window.height <= kMaxImagePixels && window.x > -kMaxSide && window.x < kMaxSide &&
         window.y > -kMaxSide && window.y < kMaxSide;
}

}  // namespace

ImageWindows checkedWindows(const std::filesystem::path& path, const PixelWindow& data,
                            const PixelWindow& display) {
  if (!isReasonable(data) || !isReasonable(display)) {
    image_file_errors::fail(
        path, "unsupported image size " + std::to_string(data.width) + "x" + std::to_string(data.height));
  }
  return {data, display};
}

FloatImage placeInDisplayWindow(const ImageWindows& windows, const std::vector<float>& block,
                                int blockChannels, const std::vector<int>& slots, float missingValue) {
  const PixelWindow& data = windows.data;
  const PixelWindow& display = windows.display;
  FloatImage image;
  image.width = int(display.width);
  image.height = int(display.height);
  image.channels = int(slots.size());
  image.pixels.assign(std::size_t(image.width) * std::size_t(image.height) * slots.size(), 0.0f);
  for (long long dataY = 0; dataY < data.height; ++dataY) {
    const long long y = data.y + dataY - display.y;
    if (y < 0 || y >= display.height) continue;
    for (long long dataX = 0; dataX < data.width; ++dataX) {
      const long long x = data.x + dataX - display.x;
      if (x < 0 || x >= display.width) continue;
      const float* source = &block[std::size_t(dataY * data.width + dataX) * std::size_t(blockChannels)];
      float* target = &image.pixels[std::size_t(y * display.width + x) * slots.size()];
      for (std::size_t c = 0; c < slots.size(); ++c)
        target[c] = slots[c] < 0 ? missingValue : source[slots[c]];
    }
  }
  return image;
}

}  // namespace spindrift
