#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "framedata/BackgroundImages.h"
#include "io/ImageFiles.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// Reads a frame's background files and keeps them while the next frame names the same files at the same
/// size, so a sequence over one static background reads and uploads it once.
class BackgroundCache {
 public:
  /// Throws Error when a named file cannot be read, or `depth` was named and holds no depth channel, or
  /// `liquid_depth` holds none.
  BackgroundImages load(const Background& background, int frame, int width, int height);

 private:
  std::string key_;
  std::uint64_t generation_ = 0;
  std::optional<FloatImage> color_;
  std::optional<FloatImage> eyeDepth_;
  std::optional<FloatImage> environment_;
  std::optional<FloatImage> liquidEyeDepth_;
};

}  // namespace spindrift
