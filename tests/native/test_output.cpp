// Output files are read back with OpenImageIO directly, not through the project's own readers.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <Imath/half.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "spindrift/Error.h"
#include "spindrift/Output.h"

namespace spindrift {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

class OutputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string testName = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    directory_ = std::filesystem::temp_directory_path() /
                 ("spindrift-output-" + std::to_string(::getpid()) + "-" + testName);
    std::filesystem::remove_all(directory_);
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  // Every file in `directory`, so a test can tell that no temporary file was left behind.
  static std::vector<std::string> filesIn(const std::filesystem::path& directory) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(directory)) {
      names.push_back(entry.path().filename().string());
    }
    return names;
  }

  std::filesystem::path directory_;
};

ImageLayer makeLayer(const std::string& name, std::vector<std::string> channels, std::vector<float> pixels) {
  ImageLayer layer;
  layer.name = name;
  layer.channels = std::move(channels);
  layer.pixels = std::move(pixels);
  return layer;
}

// A 2x1 result whose every value says which layer, channel and pixel it is.
RenderResult makeThreeLayerResult() {
  RenderResult result;
  result.width = 2;
  result.height = 1;
  result.layers.push_back(
      makeLayer("composite", {"R", "G", "B", "A"}, {0.1f, 0.2f, 0.3f, 1.0f, 1.1f, 1.2f, 1.3f, kNaN}));
  result.layers.push_back(makeLayer("depth", {"Z"}, {5.0f, 6.5f}));
  result.layers.push_back(makeLayer("normal", {"X", "Y", "Z"}, {0.0f, 0.0f, 1.0f, -1.0f, 0.0f, 0.0f}));
  return result;
}

std::string fileBytes(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(file), {});
}

// The pixels of an 8-bit PNG as stored, straight alpha, without OIIO's premultiplication on read.
std::vector<std::uint8_t> readStoredPng(const std::filesystem::path& path, OIIO::ImageSpec* spec) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path.string(), &config);
  if (!input) return {};
  *spec = input->spec();
  std::vector<std::uint8_t> pixels(std::size_t(spec->width) * spec->height * spec->nchannels);
  input->read_image(0, 0, 0, spec->nchannels, OIIO::TypeUInt8, pixels.data());
  return pixels;
}

TEST_F(OutputTest, ExrHoldsEveryLayerAsNamedFloatChannels) {
  const std::filesystem::path path = directory_ / "new" / "sub" / "frame.exr";
  writeExr(makeThreeLayerResult(), path);

  std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(input) << OIIO::geterror();
  const OIIO::ImageSpec spec = input->spec();
  EXPECT_EQ(spec.width, 2);
  EXPECT_EQ(spec.height, 1);
  EXPECT_EQ(spec.format, OIIO::TypeFloat);
  EXPECT_EQ(spec.get_string_attribute("compression"), "zip");
  std::vector<float> pixels(std::size_t(2) * spec.nchannels);
  ASSERT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeFloat, pixels.data()));

  // OpenEXR keeps channels sorted by name, so look every value up by its name.
  std::map<std::string, std::vector<float>> byName;
  for (int channel = 0; channel < spec.nchannels; ++channel) {
    byName[spec.channelnames[channel]] = {pixels[channel], pixels[spec.nchannels + channel]};
  }
  const std::map<std::string, std::vector<float>> expected = {
      {"composite.R", {0.1f, 1.1f}}, {"composite.G", {0.2f, 1.2f}}, {"composite.B", {0.3f, 1.3f}},
      {"composite.A", {1.0f, kNaN}}, {"depth.Z", {5.0f, 6.5f}},     {"normal.X", {0.0f, -1.0f}},
      {"normal.Y", {0.0f, 0.0f}},    {"normal.Z", {1.0f, 0.0f}}};
  ASSERT_EQ(byName.size(), expected.size());
  for (const auto& [name, values] : expected) {
    ASSERT_EQ(byName.count(name), 1u) << name;
    for (int pixel = 0; pixel < 2; ++pixel) {
      if (std::isnan(values[pixel])) {
        EXPECT_TRUE(std::isnan(byName[name][pixel])) << name;
      } else {
        EXPECT_EQ(byName[name][pixel], values[pixel]) << name;
      }
    }
  }
  EXPECT_EQ(filesIn(path.parent_path()), std::vector<std::string>{"frame.exr"});
}

TEST_F(OutputTest, ExrWritesTheChosenLayersWithHalfColourAcrossRowChunks) {
  // 37 x 131: an odd width, and rows that do not fill the writer's last chunk of 64.
  RenderResult result;
  result.width = 37;
  result.height = 131;
  const std::size_t pixels = 37 * 131;
  std::vector<float> colour(pixels * 4), depth(pixels), normal(pixels * 3);
  for (std::size_t i = 0; i < colour.size(); ++i)
    colour[i] = float((i * 7919) % 1000) / 997.0f;
  for (std::size_t i = 0; i < pixels; ++i)
    depth[i] = 1.0f + float(i) * 1.0001f;  // beyond half's precision
  result.layers.push_back(makeLayer("composite", {"R", "G", "B", "A"}, colour));
  result.layers.push_back(makeLayer("normal", {"X", "Y", "Z"}, normal));
  result.layers.push_back(makeLayer("depth", {"Z"}, depth));
  const std::filesystem::path path = directory_ / "chosen.exr";
  ExrOptions options;
  options.halfColor = true;
  options.compression = "zips";
  options.layers = {"depth", "composite"};
  writeExr(result, path, options);

  std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(input) << OIIO::geterror();
  const OIIO::ImageSpec spec = input->spec();
  ASSERT_EQ(spec.nchannels, 5) << "composite.RGBA and depth.Z only";
  std::vector<float> read(pixels * 5);
  ASSERT_TRUE(input->read_image(0, 0, 0, 5, OIIO::TypeFloat, read.data()));
  std::size_t wrong = 0;
  for (int channel = 0; channel < 5; ++channel) {
    const std::string& name = spec.channelnames[channel];
    if (name == "depth.Z") {
      EXPECT_EQ(spec.channelformat(channel), OIIO::TypeFloat);
      for (std::size_t i = 0; i < pixels; ++i)
        wrong += read[i * 5 + channel] != depth[i];
    } else {
      EXPECT_EQ(spec.channelformat(channel), OIIO::TypeHalf) << name;
      const int c = int(std::string("RGBA").find(name.back()));
      ASSERT_GE(c, 0) << name;
      for (std::size_t i = 0; i < pixels; ++i)
        wrong += read[i * 5 + channel] != float(Imath::half(colour[i * 4 + std::size_t(c)]));
    }
  }
  EXPECT_EQ(wrong, 0u);
}

// zlib's level is an encoder setting: every level stores the same pixels under OpenEXR's one ZIP, and the
// lower level spends less effort and so writes more bytes. A level OpenImageIO would not parse (it would fall
// back to its default silently) or a level on a codec without one is an error, as a misspelt name is.
TEST_F(OutputTest, ZipLevelsStoreTheSamePixelsAndTheFastestTheMostBytes) {
  RenderResult result;
  result.width = 160;
  result.height = 96;
  std::vector<float> colour(std::size_t(result.width) * result.height * 4);
  for (std::size_t i = 0; i < colour.size(); ++i)  // smooth ramps with some noise: what zlib's effort changes
    colour[i] = float(i % 613) / 613.0f + float((i * 2654435761u) % 17) * 1e-4f;
  result.layers.push_back(makeLayer("composite", {"R", "G", "B", "A"}, colour));
  std::map<std::string, std::uintmax_t> bytes;
  for (const std::string compression : {"zip:1", "zip:9", "zips:1"}) {
    std::string name = compression;
    std::replace(name.begin(), name.end(), ':', '_');
    const std::filesystem::path path = directory_ / (name + ".exr");
    ExrOptions options;
    options.compression = compression;
    writeExr(result, path, options);
    bytes[compression] = std::filesystem::file_size(path);
    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(path.string());
    ASSERT_TRUE(input) << OIIO::geterror();
    EXPECT_EQ(input->spec().get_string_attribute("compression"),
              compression.substr(0, compression.find(':')));
    std::vector<float> read(colour.size());
    ASSERT_TRUE(input->read_image(0, 0, 0, 4, OIIO::TypeFloat, read.data()));
    std::size_t wrong = 0;
    for (int channel = 0; channel < 4; ++channel) {  // stored sorted by name: A, B, G, R
      const int c = int(std::string("RGBA").find(input->spec().channelnames[std::size_t(channel)].back()));
      for (std::size_t pixel = 0; pixel < colour.size() / 4; ++pixel)
        wrong += read[pixel * 4 + std::size_t(channel)] != colour[pixel * 4 + std::size_t(c)];
    }
    EXPECT_EQ(wrong, 0u) << compression;
  }
  EXPECT_GT(bytes["zip:1"], bytes["zip:9"]);
  EXPECT_EQ(ExrOptions{}.compression, "zip:1");

  for (const char* valid : {"zip", "zip:1", "zips:9", "none", "piz", "dwaa"})
    EXPECT_TRUE(exrCompressionIsValid(valid)) << valid;
  for (const char* invalid : {"zip:0", "zip:10", "zip:", "zip:a", "piz:3", "none:1", "zpi", ""}) {
    EXPECT_FALSE(exrCompressionIsValid(invalid)) << invalid;
    ExrOptions options;
    options.compression = invalid;
    EXPECT_THROW(writeExr(result, directory_ / "invalid.exr", options), Error) << invalid;
  }
  EXPECT_FALSE(std::filesystem::exists(directory_ / "invalid.exr"));
}

TEST_F(OutputTest, PngEncodesLinearValuesWithTheSrgbTransferFunction) {
  RenderResult result;
  result.width = 7;
  result.height = 1;
  const std::vector<float> linear = {0.0f, 1.0f, 0.5f, 0.0031308f, kNaN, 4.0f, -1.0f};
  std::vector<float> pixels;
  for (float value : linear)
    pixels.insert(pixels.end(), {value, value, value, 1.0f});
  result.layers.push_back(makeLayer("depth", {"Z"}, std::vector<float>(7, 1.0f)));
  result.layers.push_back(makeLayer("composite", {"R", "G", "B", "A"}, pixels));
  const std::filesystem::path path = directory_ / "srgb.png";
  writePng(result, path);

  OIIO::ImageSpec spec;
  const std::vector<std::uint8_t> stored = readStoredPng(path, &spec);
  ASSERT_EQ(spec.nchannels, 4);
  ASSERT_EQ(spec.format, OIIO::TypeUInt8);
  // 0.5 linear is 0.7354 in sRGB; 0.0031308 is where the curve turns linear, 12.92 x 0.0031308 = 0.04045.
  const std::uint8_t expected[7] = {0, 255, 188, 10, 0, 255, 0};
  for (int pixel = 0; pixel < 7; ++pixel) {
    EXPECT_EQ(stored[pixel * 4 + 0], expected[pixel]) << "linear " << linear[pixel];
    EXPECT_EQ(stored[pixel * 4 + 2], expected[pixel]) << "linear " << linear[pixel];
    EXPECT_EQ(stored[pixel * 4 + 3], 255);
  }
}

TEST_F(OutputTest, PngUnpremultipliesAndKeepsAlpha) {
  RenderResult result;
  result.width = 3;
  result.height = 1;
  // Premultiplied: half-covered mid grey, fully transparent, and a NaN alpha.
  result.layers.push_back(makeLayer("composite", {"R", "G", "B", "A"},
                                    {0.25f, 0.25f, 0.0f, 0.5f, 0, 0, 0, 0, 0.5f, 0.5f, 0.5f, kNaN}));
  const std::filesystem::path path = directory_ / "alpha.png";
  writePng(result, path);

  OIIO::ImageSpec spec;
  const std::vector<std::uint8_t> stored = readStoredPng(path, &spec);
  ASSERT_EQ(stored.size(), 12u);
  EXPECT_EQ(stored[0], 188);  // 0.25 / 0.5 = 0.5 linear.
  EXPECT_EQ(stored[1], 188);
  EXPECT_EQ(stored[2], 0);
  EXPECT_EQ(stored[3], 128);  // 0.5 x 255 = 127.5, rounded half away from zero.
  EXPECT_EQ(stored[7], 0);
  EXPECT_EQ(stored[11], 0);
}

TEST_F(OutputTest, PngWithoutACompositeLayerIsAnError) {
  RenderResult result = makeThreeLayerResult();
  result.layers.erase(result.layers.begin());
  const std::filesystem::path path = directory_ / "none.png";
  EXPECT_THROW(writePng(result, path), Error);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST_F(OutputTest, AFailedWriteThrowsAndLeavesTheGoodFileAlone) {
  const std::filesystem::path path = directory_ / "frame.exr";
  writeExr(makeThreeLayerResult(), path);
  const std::string goodBytes = fileBytes(path);
  ASSERT_FALSE(goodBytes.empty());

  RenderResult broken = makeThreeLayerResult();
  broken.layers[1].pixels.pop_back();
  EXPECT_THROW(writeExr(broken, path), Error);
  EXPECT_THROW(writePng(broken, path), Error);
  EXPECT_EQ(fileBytes(path), goodBytes);
  EXPECT_EQ(filesIn(directory_), std::vector<std::string>{"frame.exr"});
}

TEST_F(OutputTest, WritingUnderARegularFileThrowsAnErrorNamingThePath) {
  const std::filesystem::path regularFile = directory_ / "not-a-directory";
  std::ofstream(regularFile) << "a file where a directory should be";
  for (const std::filesystem::path& path : {regularFile / "frame.exr", regularFile / "frame.png"}) {
    try {
      if (path.extension() == ".exr") {
        writeExr(makeThreeLayerResult(), path);
      } else {
        writePng(makeThreeLayerResult(), path);
      }
      FAIL() << "wrote " << path;
    } catch (const Error& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(path.string()), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
}

TEST_F(OutputTest, AFailedRenameRemovesTheTemporaryFile) {
  // The target is a directory with something in it: the data is written, but the rename must fail.
  const std::filesystem::path path = directory_ / "occupied.exr";
  std::filesystem::create_directories(path / "keep");
  EXPECT_THROW(writeExr(makeThreeLayerResult(), path), Error);
  EXPECT_THROW(writePng(makeThreeLayerResult(), path), Error);
  EXPECT_TRUE(std::filesystem::is_directory(path / "keep"));
  EXPECT_EQ(filesIn(directory_), std::vector<std::string>{"occupied.exr"});
}

}  // namespace
}  // namespace spindrift
