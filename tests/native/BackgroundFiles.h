#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <glm/vec3.hpp>

// Writes a background for a test as Blender would: a multilayer EXR with ViewLayer.Combined.RGBA and
// ViewLayer.Depth.Z, from a function of the pixel (column, row; row 0 at the top).
inline void writeBackgroundExr(const std::filesystem::path& path, int width, int height,
                               const std::function<glm::vec3(int, int)>& color,
                               const std::function<float(int, int)>& eyeDepth) {
  std::vector<float> pixels(std::size_t(width) * height * 5);
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column) {
      float* pixel = &pixels[(std::size_t(row) * width + column) * 5];
      const glm::vec3 rgb = color(column, row);
      pixel[0] = rgb.r;
      pixel[1] = rgb.g;
      pixel[2] = rgb.b;
      pixel[3] = 1.0f;
      pixel[4] = eyeDepth(column, row);
    }
  auto output = OIIO::ImageOutput::create(path.string());
  OIIO::ImageSpec spec(width, height, 5, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B",
                       "ViewLayer.Combined.A", "ViewLayer.Depth.Z"};
  output->open(path.string(), spec);
  output->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
  output->close();
}
