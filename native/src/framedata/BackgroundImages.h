#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "io/ImageFiles.h"

namespace spindrift {

/// The background of one frame on the CPU, already at the camera's size (prep/BackgroundCache makes it, the
/// background pass uploads it). Null images are absent.
struct BackgroundImages {
  const FloatImage* color = nullptr;           ///< RGBA, premultiplied.
  const FloatImage* eyeDepth = nullptr;        ///< Planar eye depth, one channel.
  const FloatImage* environment = nullptr;     ///< Equirectangular RGBA, any size.
  const FloatImage* liquidEyeDepth = nullptr;  ///< Planar eye depth of a render that includes the liquid.
  glm::vec3 fallbackColor{0.0f};
  std::uint64_t generation = 0;  ///< Changes whenever any image changes, so unchanged ones stay uploaded.
};

}  // namespace spindrift
