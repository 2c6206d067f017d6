#pragma once

#include <vector>

namespace spindrift {

/// An image in memory: `channels` interleaved 32-bit floats per pixel, top row first, linear colour.
struct FloatImage {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> pixels;

  bool empty() const { return pixels.empty(); }
};

}  // namespace spindrift
