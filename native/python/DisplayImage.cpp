#include "DisplayImage.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "spindrift/Error.h"

namespace spindrift::python {
namespace {

const ImageLayer& rgbaLayer(const RenderResult& result, const std::string& name) {
  for (const ImageLayer& layer : result.layers)
    if (layer.name == name) {
      if (layer.channelCount() != 4) throw Error("display image: layer " + name + " is not RGBA");
      return layer;
    }
  throw Error("display image: the frame has no layer " + name);
}

float finiteOrZero(float value) {
  return std::isfinite(value) ? value : 0.0f;
}

// The sRGB transfer function (IEC 61966-2-1) of a linear value in 0..1.
float srgbEncode(float linear) {
  return linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

std::vector<float> displayImage(const RenderResult& result) {
  const ImageLayer& liquid = rgbaLayer(result, "liquid");
  const ImageLayer& foam = rgbaLayer(result, "foam");
  const std::size_t width = std::size_t(result.width), height = std::size_t(result.height);
  std::vector<float> out(width * height * 4);
  for (std::size_t row = 0; row < height; ++row) {
    const std::size_t sourceRow = height - 1 - row;  // Layers are top row first.
    for (std::size_t column = 0; column < width; ++column) {
      const std::size_t source = (sourceRow * width + column) * 4, target = (row * width + column) * 4;
      const float foamAlpha = finiteOrZero(foam.pixels[source + 3]);
      float over[4];
      for (int c = 0; c < 4; ++c)
        over[c] = finiteOrZero(foam.pixels[source + c]) +
                  (1.0f - foamAlpha) * finiteOrZero(liquid.pixels[source + c]);
      const float alpha = std::clamp(over[3], 0.0f, 1.0f);
      // Encode the straight colour, then premultiply again: sRGB of a premultiplied value would darken edges.
      for (int c = 0; c < 3; ++c) {
        const float straight = alpha > 1e-6f ? std::clamp(over[c] / alpha, 0.0f, 1.0f) : 0.0f;
        out[target + c] = srgbEncode(straight) * alpha;
      }
      out[target + 3] = alpha;
    }
  }
  return out;
}

}  // namespace spindrift::python
