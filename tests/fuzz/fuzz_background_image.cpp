// libFuzzer harness: the background image reader (colour, depth and Cycles' light passes) through OpenEXR and
// OpenImageIO. The first byte chooses the file's extension, the rest is the file. OpenImageIO and its codecs
// are not instrumented; what is checked is Spindrift's use of them: sizes, data and display windows, channel
// lookup, alpha, resampling.
#include <cmath>
#include <cstdint>
#include <optional>

#include "FuzzInput.h"
#include "io/ImageFiles.h"
#include "spindrift/Error.h"
#include "spindrift/Limits.h"

namespace {

void checkImage(const spindrift::FloatImage& image, int channels) {
  FUZZ_REQUIRE(image.width > 0 && image.height > 0 && image.channels == channels);
  FUZZ_REQUIRE(image.pixels.size() == std::size_t(image.width) * image.height * channels);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  spindrift::setMemoryLimitBytes(std::uint64_t(512) << 20);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const kExtensions[] = {"exr", "png", "hdr", "tif", "jpg"};
  const std::string name = std::string("input.") + kExtensions[data[0] % 5];
  const std::filesystem::path path = fuzz::writeInput(data + 1, size - 1, name);
  try {
    // What the renderer reads from a background: colour, depth and light passes, each image decoded once.
    const spindrift::BackgroundFile file = spindrift::readBackgroundFile(path, true);
    checkImage(file.color, 4);
    // The resampling a background goes through when the camera's size differs.
    checkImage(spindrift::resizeImage(file.color, 1 + file.color.width / 3, 1 + file.color.height / 3, false),
               4);
    if (file.depth) {
      checkImage(*file.depth, 1);
      checkImage(spindrift::resizeImage(*file.depth, file.depth->width * 2, file.depth->height * 2, true), 1);
    }
    if (file.lightPasses)
      for (const spindrift::FloatImage& pass : *file.lightPasses)
        checkImage(pass, 4);
  } catch (const spindrift::Error&) {
    // A file without colour may still be a depth image of its own (a scene's background.depth).
    try {
      if (const std::optional<spindrift::FloatImage> depth = spindrift::readDepthImage(path))
        checkImage(*depth, 1);
    } catch (const spindrift::Error&) {
    }
  }
  return 0;
}
