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

FloatImage emptyDisplayImage(const ImageWindows& windows, int channels) {
  FloatImage image;
  image.width = int(windows.display.width);
  image.height = int(windows.display.height);
  image.channels = channels;
  image.pixels.assign(std::size_t(image.width) * std::size_t(image.height) * std::size_t(channels), 0.0f);
  return image;
}

void placeRowsInDisplayWindow(const ImageWindows& windows, const float* block, int blockChannels,
                              long long firstRow, long long rows, const std::vector<int>& slots,
                              float missingValue, FloatImage* image) {
  const PixelWindow& data = windows.data;
  const PixelWindow& display = windows.display;
  for (long long row = 0; row < rows; ++row) {
    const long long y = data.y + firstRow + row - display.y;
    if (y < 0 || y >= display.height) continue;
    for (long long dataX = 0; dataX < data.width; ++dataX) {
      const long long x = data.x + dataX - display.x;
      if (x < 0 || x >= display.width) continue;
      const float* source = block + std::size_t(row * data.width + dataX) * std::size_t(blockChannels);
      float* target = &image->pixels[std::size_t(y * display.width + x) * slots.size()];
      for (std::size_t c = 0; c < slots.size(); ++c)
        target[c] = slots[c] < 0 ? missingValue : source[slots[c]];
    }
  }
}

FloatImage placeInDisplayWindow(const ImageWindows& windows, const std::vector<float>& block,
                                int blockChannels, const std::vector<int>& slots, float missingValue) {
  FloatImage image = emptyDisplayImage(windows, int(slots.size()));
  placeRowsInDisplayWindow(windows, block.data(), blockChannels, 0, windows.data.height, slots, missingValue,
                           &image);
  return image;
}

}  // namespace spindrift
