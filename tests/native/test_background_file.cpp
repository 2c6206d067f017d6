// A background file read whole (readBackgroundFile): against the colour and depth readers and against the
// light passes' products of the channels written; each image of it decoded once; and OpenEXR images decoded
// in bands of rows against all at once. Files are written here with OpenEXR itself, as Blender writes its
// multilayer renders.

#include <algorithm>
#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "io/ImageFiles.h"
#include "io/ImageReader.h"

namespace spindrift {
namespace {

// What Blender writes with the Combined, Depth, Normal and Cycles' six light passes.
const std::vector<std::string> kBlenderChannels = {
    "ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B", "ViewLayer.Combined.A",
    "ViewLayer.Depth.Z",    "ViewLayer.DiffCol.R",  "ViewLayer.DiffCol.G",  "ViewLayer.DiffCol.B",
    "ViewLayer.DiffDir.R",  "ViewLayer.DiffDir.G",  "ViewLayer.DiffDir.B",  "ViewLayer.DiffInd.R",
    "ViewLayer.DiffInd.G",  "ViewLayer.DiffInd.B",  "ViewLayer.GlossCol.R", "ViewLayer.GlossCol.G",
    "ViewLayer.GlossCol.B", "ViewLayer.GlossDir.R", "ViewLayer.GlossDir.G", "ViewLayer.GlossDir.B",
    "ViewLayer.GlossInd.R", "ViewLayer.GlossInd.G", "ViewLayer.GlossInd.B", "ViewLayer.Normal.X",
    "ViewLayer.Normal.Y",   "ViewLayer.Normal.Z"};

// A value that says which channel and pixel it belongs to, below 1 so that products of two stay exact enough.
float marker(std::size_t channel, long long x, long long y) {
  return 0.01f * float(channel + 1) + 0.0001f * float(y * 100 + x);
}

// Writes a zip-compressed scanline EXR whose data window (dataWidth x dataHeight at dataX, dataY) lies inside
// a display window of displayWidth x displayHeight at the origin; channel c holds marker(c, x, y).
void writeExr(const std::filesystem::path& path, const std::vector<std::string>& channels, int dataX,
              int dataY, int dataWidth, int dataHeight, int displayWidth, int displayHeight) {
  const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(displayWidth - 1, displayHeight - 1));
  const Imath::Box2i data(Imath::V2i(dataX, dataY),
                          Imath::V2i(dataX + dataWidth - 1, dataY + dataHeight - 1));
  Imf::Header header(display, data);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const std::string& name : channels)
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
  std::vector<std::vector<float>> planes(channels.size());
  Imf::FrameBuffer frameBuffer;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    planes[c].resize(std::size_t(dataWidth) * std::size_t(dataHeight));
    for (int y = 0; y < dataHeight; ++y)
      for (int x = 0; x < dataWidth; ++x)
        planes[c][std::size_t(y) * std::size_t(dataWidth) + std::size_t(x)] = marker(c, dataX + x, dataY + y);
    frameBuffer.insert(channels[c], Imf::Slice::Make(Imf::FLOAT, planes[c].data(), data, sizeof(float),
                                                     sizeof(float) * std::size_t(dataWidth)));
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(frameBuffer);
  file.writePixels(dataHeight);
}

class BackgroundFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string testName = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    directory_ = std::filesystem::temp_directory_path() /
                 ("spindrift-background-file-" + std::to_string(::getpid()) + "-" + testName);
    std::filesystem::remove_all(directory_);
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  std::filesystem::path directory_;
};

TEST_F(BackgroundFileTest, ReadsWhatTheReadersReadAndTheLightPassesProducts) {
  const std::filesystem::path path = directory_ / "render.exr";
  const int dataX = 2, dataY = 1, width = 9, height = 6;
  writeExr(path, kBlenderChannels, dataX, dataY, 5, 4, width, height);

  const BackgroundFile file = readBackgroundFile(path, true);
  EXPECT_EQ(file.color.pixels, readColorImage(path).pixels);
  ASSERT_TRUE(file.depth);
  EXPECT_EQ(file.depth->pixels, readDepthImage(path)->pixels);
  ASSERT_TRUE(file.lightPasses);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ((*file.lightPasses)[i].width, width);
    EXPECT_EQ((*file.lightPasses)[i].height, height);
    EXPECT_EQ((*file.lightPasses)[i].channels, 4);
  }

  // The light from the passes as the lit background takes it, at every pixel: the written channels' products
  // inside the data window (5 x 4 at (2, 1)), 0 outside it; alpha DiffDir's mean, 0 for the other two.
  for (long long y = 0; y < height; ++y)
    for (long long x = 0; x < width; ++x) {
      const bool inData = x >= dataX && x < dataX + 5 && y >= dataY && y < dataY + 4;
      const auto at = [&](std::size_t image, std::size_t channel) {
        return (*file.lightPasses)[image].pixels[std::size_t((y * width + x) * 4) + channel];
      };
      const auto written = [&](std::size_t channel) { return inData ? marker(channel, x, y) : 0.0f; };
      for (std::size_t c = 0; c < 3; ++c) {
        const float diffCol = written(5 + c), diffDir = written(8 + c), diffInd = written(11 + c);
        const float glossCol = written(14 + c), glossDir = written(17 + c), glossInd = written(20 + c);
        EXPECT_FLOAT_EQ(at(0, c), diffCol * diffDir) << x << ", " << y;
        EXPECT_FLOAT_EQ(at(1, c), glossCol * glossDir) << x << ", " << y;
        EXPECT_FLOAT_EQ(at(2, c), diffCol * diffInd + glossCol * glossInd) << x << ", " << y;
      }
      EXPECT_FLOAT_EQ(at(0, 3), (written(8) + written(9) + written(10)) / 3.0f) << x << ", " << y;
      EXPECT_EQ(at(1, 3), 0.0f);
      EXPECT_EQ(at(2, 3), 0.0f);
    }
  const long long x = 4, y = 3;
  EXPECT_EQ(file.color.pixels[0], 0.0f);
  EXPECT_EQ(file.color.pixels[std::size_t((y * width + x) * 4) + 3], marker(3, x, y));

  EXPECT_FALSE(readBackgroundFile(path, false).depth);
}

TEST_F(BackgroundFileTest, WithoutLightPassesOrDepthItHasNone) {
  const std::filesystem::path path = directory_ / "plain.exr";
  writeExr(path, {"R", "G", "B"}, 0, 0, 3, 2, 3, 2);
  const BackgroundFile file = readBackgroundFile(path, true);
  EXPECT_EQ(file.color.pixels, readColorImage(path).pixels);
  EXPECT_EQ(file.color.pixels[3], 1.0f);  // no alpha: opaque
  EXPECT_FALSE(file.depth);
  EXPECT_FALSE(file.lightPasses);
}

// An image reader that serves names and counts how it is asked for pixels.
class CountingReader final : public ImageReader {
 public:
  explicit CountingReader(std::vector<std::vector<std::string>> names) : names_(std::move(names)) {}

  int imageCount() const override { return int(names_.size()); }
  const std::vector<std::string>& channelNames(int image) const override { return names_.at(image); }
  ColorEncoding colorEncoding(int) const override { return {}; }
  FloatImage readChannels(int, const std::vector<int>& channels, float) override {
    ++channelReads;
    return FloatImage{1, 1, int(channels.size()), std::vector<float>(channels.size(), 0.5f)};
  }
  std::vector<FloatImage> readChannelSets(int image, const std::vector<ChannelSet>& sets) override {
    setReads.push_back({image, sets.size()});
    std::vector<FloatImage> images;
    for (const ChannelSet& set : sets) {
      FloatImage one{1, 1, int(set.channels.size()), {}};
      for (int channel : set.channels)
        one.pixels.push_back(channel < 0 ? set.missingValue : float(channel + 1));
      images.push_back(one);
    }
    return images;
  }

  int channelReads = 0;
  std::vector<std::pair<int, std::size_t>> setReads;  // (image, sets) of each call

 private:
  std::vector<std::vector<std::string>> names_;
};

TEST(BackgroundFileDecoding, EachImageOfTheFileIsReadOnce) {
  CountingReader oneImage({kBlenderChannels});
  const BackgroundFile file = readBackgroundFile(oneImage, "render.exr", true);
  EXPECT_EQ(oneImage.channelReads, 0);
  ASSERT_EQ(oneImage.setReads.size(), 1u);
  EXPECT_EQ(oneImage.setReads[0].second, 8u);  // the colour, the depth and the six light passes
  EXPECT_EQ(file.color.pixels, (std::vector<float>{1.0f, 2.0f, 3.0f, 4.0f}));
  ASSERT_TRUE(file.depth);
  EXPECT_EQ(file.depth->pixels, std::vector<float>{5.0f});
  ASSERT_TRUE(file.lightPasses);
  // Direct diffuse: DiffCol (channels 6-8) x DiffDir (9-11), alpha DiffDir's mean.
  EXPECT_EQ((*file.lightPasses)[0].pixels,
            (std::vector<float>{6.0f * 9.0f, 7.0f * 10.0f, 8.0f * 11.0f, 10.0f}));

  // Colour in one part, depth in another: one read of each.
  CountingReader twoImages({{"depth.Z"}, {"R", "G", "B", "A"}});
  const BackgroundFile parts = readBackgroundFile(twoImages, "parts.exr", true);
  EXPECT_EQ(twoImages.channelReads, 0);
  ASSERT_EQ(twoImages.setReads.size(), 2u);
  EXPECT_EQ(twoImages.setReads[0], (std::pair<int, std::size_t>{1, 1}));
  EXPECT_EQ(twoImages.setReads[1], (std::pair<int, std::size_t>{0, 1}));
  ASSERT_TRUE(parts.depth);
  EXPECT_EQ(parts.depth->pixels, std::vector<float>{1.0f});
  EXPECT_FALSE(parts.lightPasses);
}

TEST_F(BackgroundFileTest, AnExrDecodedInBandsOfRowsIsTheSameAsWhole) {
  // 600 rows from row 3 of a 610-row display window: bands of 256, 256 and 88 rows.
  const std::filesystem::path path = directory_ / "tall.exr";
  writeExr(path, {"R", "G", "Z"}, 1, 3, 4, 600, 6, 610);
  const std::unique_ptr<ImageReader> whole = openExrImage(path);
  const std::unique_ptr<ImageReader> banded = openExrImage(path, 1);
  const std::vector<std::string>& names = whole->channelNames(0);  // as the file sorts them
  const auto index = [&](const std::string& name) {
    return int(std::find(names.begin(), names.end(), name) - names.begin());
  };
  const std::vector<ChannelSet> sets = {
      {{index("R"), index("G"), -1}, 1.0f}, {{index("Z")}, 0.0f}, {{-1}, 0.25f}};
  const std::vector<FloatImage> wholeSets = whole->readChannelSets(0, sets);
  const std::vector<FloatImage> bandedSets = banded->readChannelSets(0, sets);
  ASSERT_EQ(wholeSets.size(), 3u);
  ASSERT_EQ(bandedSets.size(), 3u);
  for (std::size_t s = 0; s < sets.size(); ++s) {
    EXPECT_EQ(bandedSets[s].pixels, wholeSets[s].pixels) << s;
    EXPECT_EQ(wholeSets[s].pixels, whole->readChannels(0, sets[s].channels, sets[s].missingValue).pixels)
        << s;
  }
  // At (2, 500), in the last band: R and G as written, the missing channel its value; 0 outside the data
  // window (row 0).
  const FloatImage& rg = bandedSets[0];
  const std::size_t pixel = std::size_t(500 * 6 + 2);
  EXPECT_EQ(rg.pixels[pixel * 3 + 0], marker(0, 2, 500));
  EXPECT_EQ(rg.pixels[pixel * 3 + 1], marker(1, 2, 500));
  EXPECT_EQ(rg.pixels[pixel * 3 + 2], 1.0f);
  EXPECT_EQ(bandedSets[1].pixels[pixel], marker(2, 2, 500));
  EXPECT_EQ(bandedSets[2].pixels[pixel], 0.25f);
  EXPECT_EQ(rg.pixels[2 * 3 + 2], 0.0f);
  EXPECT_EQ(bandedSets[2].pixels[2], 0.0f);
}

}  // namespace
}  // namespace spindrift
