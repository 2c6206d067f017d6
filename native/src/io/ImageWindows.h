#pragma once

#include <filesystem>
#include <vector>

#include "spindrift/FloatImage.h"

namespace spindrift {

/// More pixels than this is certainly a corrupt header or a mistake, and refusing it keeps it from becoming
/// an allocation failure instead of an Error.
constexpr long long kMaxImagePixels = 1LL << 30;

/// A rectangle of pixels in an image file's coordinates.
struct PixelWindow {
  long long x = 0, y = 0, width = 0, height = 0;
};

/// The pixels a file stores (data) and the image they belong to (display), checked.
struct ImageWindows {
  PixelWindow data, display;
};

/// Throws Error naming the file when either window is empty or larger than any real image (a corrupt
/// header, which must not become an allocation failure).
ImageWindows checkedWindows(const std::filesystem::path& path, const PixelWindow& data,
                            const PixelWindow& display);

/// The image over the display window from `block` (the data window's pixels, `blockChannels` floats each):
/// channel c is the block's channel slots[c], or `missingValue` where slots[c] is -1. Pixels outside the data
/// window are 0.
FloatImage placeInDisplayWindow(const ImageWindows& windows, const std::vector<float>& block,
                                int blockChannels, const std::vector<int>& slots, float missingValue);

/// An image of the display window's size with `channels` channels, every pixel 0.
FloatImage emptyDisplayImage(const ImageWindows& windows, int channels);

/// Places `rows` rows of the data window, from row `firstRow` on (counted from its top), into `image` (from
/// emptyDisplayImage) as placeInDisplayWindow places the whole block: `block` holds those rows alone.
void placeRowsInDisplayWindow(const ImageWindows& windows, const float* block, int blockChannels,
                              long long firstRow, long long rows, const std::vector<int>& slots,
                              float missingValue, FloatImage* image);

}  // namespace spindrift
