// What a render loads: OpenEXR alone for EXR in and out (and libpng for --png), OpenImageIO's plugin only for
// a background in another format (docs/frame-cost.md, "What a process pays before its frame"). The dynamic
// loader's own log (LD_DEBUG=libs) says which libraries a run of the command line loaded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include "CliCommand.h"
#include "TempDirectory.h"

namespace {

constexpr int kSize = 32;
constexpr float kLinear[3] = {0.05f, 0.2f, 0.6f};

float srgbFromLinear(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

// A uniform background: linear float in an EXR, or the same colour sRGB-encoded in an 8-bit PNG.
void writeBackground(const std::filesystem::path& path, bool png) {
  OIIO::ImageSpec spec(kSize, kSize, 3, png ? OIIO::TypeUInt8 : OIIO::TypeFloat);
  std::vector<float> pixels;
  for (int i = 0; i < kSize * kSize; ++i)
    for (float value : kLinear)
      pixels.push_back(png ? srgbFromLinear(value) : value);
  std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(output && output->open(path.string(), spec)) << OIIO::geterror();
  ASSERT_TRUE(output->write_image(OIIO::TypeFloat, pixels.data()));
  ASSERT_TRUE(output->close());
}

// A small body of water in the middle over the background.
std::filesystem::path writeScene(const TempDirectory& directory, const std::string& background) {
  directory.write(
      "p.ply",
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float "
      "z\nend_header\n0 0 0\n0.1 0 0\n");
  return directory.write("scene.json", R"({"version": 1,
      "camera": {"width": 32, "height": 32, "fov_y_deg": 40, "position": [0, -3, 0], "target": [0, 0, 0],
                 "up": [0, 0, 1]},
      "particles": [{"path": "p.ply", "radius": 0.2}],
      "background": {"image": ")" + background +
                                           R"("}})");
}

// The end of a long log, where the command's own message is.
std::string lastLines(const std::string& text) {
  return text.substr(text.size() - std::min<std::size_t>(2000, text.size()));
}

// The composite's corner pixel (background only).
std::vector<float> cornerOf(const std::filesystem::path& exr) {
  OIIO::ImageBuf image(exr.string());
  std::vector<float> corner;
  for (const char* name : {"composite.R", "composite.G", "composite.B"}) {
    const int channel = image.spec().channelindex(name);
    EXPECT_GE(channel, 0) << name;
    corner.push_back(image.getchannel(0, 0, 0, channel));
  }
  return corner;
}

TEST(ImageLibraries, AnExrRenderWithAnExrBackgroundNeverLoadsOpenImageIO) {
  TempDirectory directory;
  writeBackground(directory.path() / "background.exr", false);
  const std::filesystem::path scene = writeScene(directory, "background.exr");
  const CommandResult run =
      runCli("render -q " + scene.string() + " -o " + (directory.path() / "out.exr").string() + " --png " +
                 (directory.path() / "out.png").string(),
             "LD_DEBUG=libs");
  ASSERT_EQ(run.exitCode, 0) << lastLines(run.stderrText);
  // The log is there (the loader does log), and it names no OpenImageIO library.
  EXPECT_NE(run.stderrText.find("libOpenEXR"), std::string::npos);
  EXPECT_NE(run.stderrText.find("libpng16"), std::string::npos);
  EXPECT_EQ(run.stderrText.find("libOpenImageIO"), std::string::npos);
  EXPECT_EQ(run.stderrText.find("libspindrift_oiio"), std::string::npos);
  const std::vector<float> corner = cornerOf(directory.path() / "out.exr");
  for (int c = 0; c < 3; ++c)
    EXPECT_FLOAT_EQ(corner[std::size_t(c)], kLinear[c]) << c;
}

TEST(ImageLibraries, APngBackgroundIsReadThroughTheOpenImageIOPluginAsTheSameColour) {
  TempDirectory directory;
  writeBackground(directory.path() / "background.png", true);
  const std::filesystem::path scene = writeScene(directory, "background.png");
  const CommandResult run = runCli(
      "render -q " + scene.string() + " -o " + (directory.path() / "out.exr").string(), "LD_DEBUG=libs");
  ASSERT_EQ(run.exitCode, 0) << lastLines(run.stderrText);
  EXPECT_NE(run.stderrText.find("libspindrift_oiio.so"), std::string::npos);
  EXPECT_NE(run.stderrText.find("libOpenImageIO"), std::string::npos);
  // 8-bit sRGB holds each value to within half a step of its encoding: under 0.004 in linear up to 0.6.
  const std::vector<float> corner = cornerOf(directory.path() / "out.exr");
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(corner[std::size_t(c)], kLinear[c], 0.004f) << c;
}

}  // namespace
