#include "Readback.h"

#include <algorithm>

#include "spindrift/Error.h"

namespace spindrift {

ImageLayer readLayer(const Texture2D& texture, const std::string& name, const std::vector<std::string>& channels) {
  const std::size_t channelCount = channels.size();
  const GLenum format = channelCount == 1 ? GL_RED : channelCount == 2 ? GL_RG : channelCount == 3 ? GL_RGB : GL_RGBA;
  const std::size_t rowFloats = std::size_t(texture.width) * channelCount;
  std::vector<float> bottomFirst(rowFloats * std::size_t(texture.height));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(texture.id(), 0, format, GL_FLOAT, GLsizei(bottomFirst.size() * sizeof(float)), bottomFirst.data());
  checkGlError(("reading back " + name).c_str());
  ImageLayer layer{name, channels, std::vector<float>(bottomFirst.size())};
  for (int row = 0; row < texture.height; ++row)
    std::copy_n(bottomFirst.data() + std::size_t(texture.height - 1 - row) * rowFloats, rowFloats,
                layer.pixels.data() + std::size_t(row) * rowFloats);
  return layer;
}

ImageLayer filledLayer(int width, int height, const std::string& name, const std::vector<std::string>& channels,
                       float value) {
  return {name, channels, std::vector<float>(std::size_t(width) * std::size_t(height) * channels.size(), value)};
}

}  // namespace spindrift
