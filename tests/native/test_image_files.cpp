// Images are written here with OpenImageIO directly, as Blender and image editors would write them, and read
// back through io/ImageFiles.h.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include "io/ImageFiles.h"
#include "spindrift/Error.h"

namespace spindrift {
namespace {

// A fresh directory per test, removed afterwards.
class ImageFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string testName = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    directory_ = std::filesystem::temp_directory_path() /
                 ("spindrift-image-files-" + std::to_string(::getpid()) + "-" + testName);
    std::filesystem::remove_all(directory_);
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  std::filesystem::path directory_;
};

// Writes `pixels` (interleaved, top row first) with OIIO as `fileType`, with the channel names in the given
// order.
template <typename Pixel>
void writeImage(const std::filesystem::path& path, int width, int height,
                const std::vector<std::string>& channelNames, const std::vector<Pixel>& pixels,
                OIIO::TypeDesc fileType, bool unassociatedAlpha = false) {
  OIIO::ImageSpec spec(width, height, int(channelNames.size()), fileType);
  spec.channelnames = channelNames;
  if (unassociatedAlpha) spec.attribute("oiio:UnassociatedAlpha", 1);
  std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(output && output->open(path.string(), spec)) << OIIO::geterror();
  ASSERT_TRUE(output->write_image(OIIO::BaseTypeFromC<Pixel>::value, pixels.data()));
  ASSERT_TRUE(output->close());
}

// A value that says which channel and pixel it belongs to, so a mix-up of either shows.
float marker(int channel, int x, int y) {
  return float(channel * 100 + y * 10 + x);
}

float linearFromSrgb(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

std::vector<char> fileBytes(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(file), {});
}

void writeBytes(const std::filesystem::path& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
}

// Offset of the size field of the header attribute `name` of type `type`.
std::size_t attributeSizeOffset(const std::vector<char>& bytes, const std::string& name,
                                const std::string& type) {
  const std::string key = name + '\0' + type + '\0';
  const auto found = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
  EXPECT_NE(found, bytes.end()) << name;
  return std::size_t(found - bytes.begin()) + key.size();
}

void putInt32(std::vector<char>* bytes, std::size_t at, std::int32_t value) {
  for (int i = 0; i < 4; ++i)
    (*bytes)[at + i] = char((std::uint32_t(value) >> (8 * i)) & 0xff);
}

// The error names the file and says what the header claimed.
void expectRefused(const std::filesystem::path& path, const std::string& claim) {
  try {
    readColorImage(path);
    FAIL() << path << " was read";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(claim), std::string::npos) << message;
  }
}

// Blender's multilayer EXR, channels deliberately out of order, with an AO layer whose RGB must not be
// taken for colour and a Mist layer whose Z must not be taken for depth.
TEST_F(ImageFilesTest, ReadsCombinedAndDepthFromABlenderMultilayerExrByName) {
  const std::vector<std::string> names = {"ViewLayer.Normal.X", "ViewLayer.Combined.B", "ViewLayer.AO.R",
                                          "ViewLayer.Depth.Z",  "ViewLayer.Combined.A", "ViewLayer.AO.G",
                                          "ViewLayer.Mist.Z",   "ViewLayer.Combined.R", "ViewLayer.AO.B",
                                          "ViewLayer.Normal.Z", "ViewLayer.Combined.G", "ViewLayer.Normal.Y"};
  const int width = 3, height = 2;
  std::vector<float> pixels;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      for (int channel = 0; channel < int(names.size()); ++channel)
        pixels.push_back(marker(channel, x, y));
    }
  }
  const std::filesystem::path path = directory_ / "render.exr";
  writeImage(path, width, height, names, pixels, OIIO::TypeFloat);

  const FloatImage color = readColorImage(path);
  ASSERT_EQ(color.width, width);
  ASSERT_EQ(color.height, height);
  ASSERT_EQ(color.channels, 4);
  const int red = 7, green = 10, blue = 1, alpha = 4, depth = 3;  // Indices into `names`.
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float* pixel = &color.pixels[(y * width + x) * 4];
      EXPECT_EQ(pixel[0], marker(red, x, y));
      EXPECT_EQ(pixel[1], marker(green, x, y));
      EXPECT_EQ(pixel[2], marker(blue, x, y));
      EXPECT_EQ(pixel[3], marker(alpha, x, y));
    }
  }

  const std::optional<FloatImage> depthImage = readDepthImage(path);
  ASSERT_TRUE(depthImage.has_value());
  ASSERT_EQ(depthImage->channels, 1);
  ASSERT_EQ(depthImage->width, width);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x)
      EXPECT_EQ(depthImage->pixels[y * width + x], marker(depth, x, y));
  }
}

TEST_F(ImageFilesTest, ReadsPlainRgbWithOpaqueAlphaAndPlainZ) {
  const std::filesystem::path path = directory_ / "plain.exr";
  writeImage(path, 2, 1, {"R", "G", "B", "Z"},
             std::vector<float>{0.5f, 0.25f, 2.0f, 7.0f, 0.0f, 1.0f, 3.0f, 9.5f},
             OIIO::TypeHalf);  // Blender's default EXR depth.

  const FloatImage color = readColorImage(path);
  ASSERT_EQ(color.channels, 4);
  EXPECT_EQ(color.pixels, (std::vector<float>{0.5f, 0.25f, 2.0f, 1.0f, 0.0f, 1.0f, 3.0f, 1.0f}));
  const std::optional<FloatImage> depth = readDepthImage(path);
  ASSERT_TRUE(depth.has_value());
  EXPECT_EQ(depth->pixels, (std::vector<float>{7.0f, 9.5f}));
}

TEST_F(ImageFilesTest, ReadsLowerCaseDepthLayer) {
  const std::filesystem::path path = directory_ / "depth.exr";
  writeImage(path, 1, 1, {"depth.Z"}, std::vector<float>{4.25f}, OIIO::TypeFloat);
  const std::optional<FloatImage> depth = readDepthImage(path);
  ASSERT_TRUE(depth.has_value());
  EXPECT_EQ(depth->pixels, std::vector<float>{4.25f});
  // A depth-only file has no colour, and says so.
  try {
    readColorImage(path);
    FAIL() << "a depth-only image was read as colour";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
  }
}

TEST_F(ImageFilesTest, DecodesSrgbPngAndPremultipliesItsAlpha) {
  const std::filesystem::path path = directory_ / "background.png";
  // Stored as an image editor stores PNG: sRGB-encoded colour with unassociated alpha.
  const std::vector<std::uint8_t> stored = {255, 128, 0, 128, 10, 20, 30, 255};
  writeImage(path, 2, 1, {"R", "G", "B", "A"}, stored, OIIO::TypeUInt8, /*unassociatedAlpha=*/true);

  const FloatImage color = readColorImage(path);
  ASSERT_EQ(color.width, 2);
  ASSERT_EQ(color.channels, 4);
  const float halfAlpha = 128.0f / 255.0f;
  EXPECT_NEAR(color.pixels[0], 1.0f * halfAlpha, 1e-5f);
  EXPECT_NEAR(color.pixels[1], linearFromSrgb(128.0f / 255.0f) * halfAlpha, 1e-5f);
  EXPECT_NEAR(color.pixels[2], 0.0f, 1e-6f);
  EXPECT_NEAR(color.pixels[3], halfAlpha, 1e-6f);
  EXPECT_NEAR(color.pixels[4], linearFromSrgb(10.0f / 255.0f), 1e-6f);
  EXPECT_NEAR(color.pixels[5], linearFromSrgb(20.0f / 255.0f), 1e-6f);
  EXPECT_NEAR(color.pixels[6], linearFromSrgb(30.0f / 255.0f), 1e-6f);
  EXPECT_NEAR(color.pixels[7], 1.0f, 1e-6f);
  EXPECT_FALSE(readDepthImage(path).has_value());
}

// libpng allocates what a chunk claims before reading it (fuzz_background_image: a 110-byte file claiming 3.6
// GB). A chunk longer than the file is refused first, by name; a valid PNG, with its chunks walked, still
// reads.
TEST_F(ImageFilesTest, PngChunkLongerThanTheFileIsRefusedBeforeDecoding) {
  const std::filesystem::path good = directory_ / "good.png";
  writeImage(good, 2, 1, {"R", "G", "B"}, std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6}, OIIO::TypeUInt8);
  EXPECT_EQ(readColorImage(good).width, 2);

  std::vector<char> bytes = fileBytes(good);
  // After the signature and IHDR (8 + 25 bytes), an ancillary chunk claiming 0xda2ab66e bytes.
  const std::vector<char> claim = {char(0xda), char(0x2a), char(0xb6), char(0x6e), 'n', 'u', 'l', 'l'};
  bytes.insert(bytes.begin() + 33, claim.begin(), claim.end());
  for (const char* name : {"claims.png", "claims.tif"}) {  // by its signature, whatever its extension
    writeBytes(directory_ / name, bytes);
    expectRefused(directory_ / name, "chunk 'null' claims 3660232302 bytes");
  }
}

// OpenImageIO 2.4 reads a Photoshop APP13 segment's IPTC block with the size the block claims, past the
// segment (fuzz_background_image: a heap over-read). Such a JPEG is refused; one whose block fits still
// reads.
TEST_F(ImageFilesTest, JpegIptcBlockLongerThanItsSegmentIsRefused) {
  const std::filesystem::path plain = directory_ / "plain.jpg";
  writeImage(plain, 2, 1, {"R", "G", "B"}, std::vector<std::uint8_t>{10, 20, 30, 40, 50, 60},
             OIIO::TypeUInt8);
  const std::vector<char> bytes = fileBytes(plain);
  // APP13 after the start of image: "Photoshop 3.0\0", "8BIM", resource 1028, 4 skipped bytes, the IPTC size,
  // then an IPTC record 1C 02 78 00 02 "hi" (7 bytes).
  auto withIptc = [&](unsigned claimedSize) {
    std::vector<char> segment = {'P',
                                 'h',
                                 'o',
                                 't',
                                 'o',
                                 's',
                                 'h',
                                 'o',
                                 'p',
                                 ' ',
                                 '3',
                                 '.',
                                 '0',
                                 '\0',
                                 '8',
                                 'B',
                                 'I',
                                 'M',
                                 0x04,
                                 0x04,
                                 0,
                                 0,
                                 0,
                                 0,
                                 char(claimedSize >> 8),
                                 char(claimedSize & 0xff),
                                 0x1c,
                                 0x02,
                                 0x78,
                                 0x00,
                                 0x02,
                                 'h',
                                 'i'};
    const std::size_t length = segment.size() + 2;
    std::vector<char> result(bytes.begin(), bytes.begin() + 2);
    for (const char byte : {char(0xff), char(0xed), char(length >> 8), char(length & 0xff)})
      result.push_back(byte);
    result.insert(result.end(), segment.begin(), segment.end());
    result.insert(result.end(), bytes.begin() + 2, bytes.end());
    return result;
  };
  writeBytes(directory_ / "fits.jpg", withIptc(7));
  EXPECT_EQ(readColorImage(directory_ / "fits.jpg").width, 2);
  // The other segments OpenImageIO reads past: an ICC segment without its sequence bytes, and an APP1 segment
  // that ends inside the name strcmp compares it with.
  auto withSegment = [&](char code, const std::string& segment) {
    const std::size_t length = segment.size() + 2;
    std::vector<char> result(bytes.begin(), bytes.begin() + 2);
    for (const char byte : {char(0xff), code, char(length >> 8), char(length & 0xff)})
      result.push_back(byte);
    result.insert(result.end(), segment.begin(), segment.end());
    result.insert(result.end(), bytes.begin() + 2, bytes.end());
    return result;
  };
  const std::pair<std::vector<char>, const char*> cutShort[] = {
      {withSegment(char(0xe2), std::string("ICC_PROFILE\0", 12)), "ICC profile segment is cut short"},
      {withSegment(char(0xe1), "Exi"), "ends inside the name it is compared with"}};
  for (const auto& [file, message] : cutShort) {
    writeBytes(directory_ / "cut_short.jpg", file);
    expectRefused(directory_ / "cut_short.jpg", message);
  }
  for (const char* name : {"overruns.jpg", "overruns.png"}) {  // by its marker, whatever its extension
    writeBytes(directory_ / name, withIptc(0x5900));
    expectRefused(directory_ / name, "IPTC block claims more than its APP13 segment holds (33 bytes)");
  }
}

TEST_F(ImageFilesTest, RepeatsGreyToRgbWithOpaqueAlpha) {
  const std::filesystem::path path = directory_ / "grey.png";
  writeImage(path, 2, 2, {"Y"}, std::vector<std::uint8_t>{0, 255, 128, 64}, OIIO::TypeUInt8);

  const FloatImage color = readColorImage(path);
  ASSERT_EQ(color.width, 2);
  ASSERT_EQ(color.height, 2);
  ASSERT_EQ(color.channels, 4);
  const float expected[4] = {0.0f, 1.0f, linearFromSrgb(128.0f / 255.0f), linearFromSrgb(64.0f / 255.0f)};
  for (int pixel = 0; pixel < 4; ++pixel) {
    for (int channel = 0; channel < 3; ++channel) {
      EXPECT_NEAR(color.pixels[pixel * 4 + channel], expected[pixel], 1e-6f) << pixel;
    }
    EXPECT_EQ(color.pixels[pixel * 4 + 3], 1.0f);
  }
}

TEST_F(ImageFilesTest, PlacesTheDataWindowInsideTheDisplayWindow) {
  const std::filesystem::path path = directory_ / "window.exr";
  OIIO::ImageSpec spec(1, 1, 3, OIIO::TypeFloat);
  spec.x = 2;
  spec.y = 1;
  spec.full_width = 3;
  spec.full_height = 2;
  std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(output->open(path.string(), spec));
  const float rgb[3] = {0.5f, 0.75f, 1.0f};
  ASSERT_TRUE(output->write_image(OIIO::TypeFloat, rgb));
  ASSERT_TRUE(output->close());

  const FloatImage color = readColorImage(path);
  ASSERT_EQ(color.width, 3);
  ASSERT_EQ(color.height, 2);
  const float* lastPixel = &color.pixels[(1 * 3 + 2) * 4];
  EXPECT_EQ(lastPixel[0], 0.5f);
  EXPECT_EQ(lastPixel[1], 0.75f);
  EXPECT_EQ(lastPixel[2], 1.0f);
  EXPECT_EQ(color.pixels[0], 0.0f);
}

TEST_F(ImageFilesTest, MissingOrCorruptFilesThrowErrorsNamingThem) {
  const std::filesystem::path missing = directory_ / "missing.exr";
  EXPECT_THROW(readColorImage(missing), Error);
  EXPECT_THROW(readDepthImage(missing), Error);

  const std::filesystem::path corrupt = directory_ / "corrupt.exr";
  std::ofstream(corrupt) << "not an image at all";
  try {
    readColorImage(corrupt);
    FAIL() << "a corrupt file was read";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(corrupt.string()), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// OpenEXR 3.1 allocates what a header claims before it finds the file too short (2 GB zero-filled for a
// string attribute of an 893-byte file, found by fuzz_background_image): such files are refused first.
TEST_F(ImageFilesTest, RefusesAnExrWhoseHeaderClaimsMoreThanTheFileHolds) {
  const std::filesystem::path good = directory_ / "good.exr";
  const std::vector<float> pixels(16 * 8 * 4, 0.5f);
  writeImage(good, 16, 8, {"R", "G", "B", "A"}, pixels, OIIO::TypeDesc::HALF);
  {
    std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create("tiled.exr");
    OIIO::ImageSpec spec(16, 8, 4, OIIO::TypeDesc::HALF);
    spec.tile_width = spec.tile_height = 4;
    spec.attribute("Software", "a string attribute to corrupt");
    ASSERT_TRUE(output->open((directory_ / "tiled.exr").string(), spec));
    ASSERT_TRUE(output->write_image(OIIO::TypeFloat, pixels.data()));
    ASSERT_TRUE(output->close());
  }
  EXPECT_EQ(readColorImage(good).pixels, pixels);
  EXPECT_EQ(readColorImage(directory_ / "tiled.exr").pixels, pixels);
  const std::vector<char> tiledBytes = fileBytes(directory_ / "tiled.exr");

  std::vector<char> longString = tiledBytes;
  putInt32(&longString, attributeSizeOffset(longString, "Software", "string"), 0x7ff00000);
  writeBytes(directory_ / "long_string.exr", longString);
  expectRefused(directory_ / "long_string.exr", "attribute \"Software\" claims 2146435072 bytes");

  std::vector<char> negative = tiledBytes;
  putInt32(&negative, attributeSizeOffset(negative, "Software", "string"), -5);
  writeBytes(directory_ / "negative.exr", negative);
  expectRefused(directory_ / "negative.exr", "claims -5 bytes");

  // 4x4 tiles over a 16 x 2^24 window: 2^24 offsets of 8 bytes in a file of a few hundred bytes.
  std::vector<char> tallTiled = tiledBytes;
  putInt32(&tallTiled, attributeSizeOffset(tallTiled, "dataWindow", "box2i") + 4 + 12, (1 << 24) - 1);
  writeBytes(directory_ / "tall_tiled.exr", tallTiled);
  expectRefused(directory_ / "tall_tiled.exr", "chunks");

  std::vector<char> tallScanlines = fileBytes(good);
  putInt32(&tallScanlines, attributeSizeOffset(tallScanlines, "dataWindow", "box2i") + 4 + 12, 1 << 30);
  writeBytes(directory_ / "tall_scanlines.exr", tallScanlines);
  expectRefused(directory_ / "tall_scanlines.exr", "chunks");

  std::vector<char> cut(tiledBytes.begin(), tiledBytes.begin() + 12);  // inside the first name
  writeBytes(directory_ / "cut.exr", cut);
  expectRefused(directory_ / "cut.exr", "cut off");

  // A name past 31 characters without the long-names flag: OpenEXR would read its first 32 bytes as the name
  // and the rest as the type and a size (fuzz_background_image: 1.8 GB).
  std::vector<char> longName(tiledBytes.begin(), tiledBytes.begin() + 8);
  longName[5] &= ~0x04;  // the long-names flag, bit 10 of the version field
  const std::string name(40, 'n');
  longName.insert(longName.end(), name.begin(), name.end());
  for (const char tail : {'\0', 's', 't', 'r', 'i', 'n', 'g', '\0', '\1', '\0', '\0', '\0', 'x', '\0'})
    longName.push_back(tail);
  writeBytes(directory_ / "long_name.exr", longName);
  expectRefused(directory_ / "long_name.exr", "longer than 31 characters");
}

// OpenEXR reads a value by its type, not by its size: a channel list to its empty name, a box2i as 16 bytes,
// a string list as the lengths inside it claim.
// A size that says otherwise would make OpenEXR parse the rest of the header from another byte than the check
// did (fuzz_background_image: a channel list longer than its size hid a 1.6 GB string from the check).
TEST_F(ImageFilesTest, RefusesAnExrWhoseAttributeSizeDisagreesWithItsType) {
  const std::filesystem::path good = directory_ / "good.exr";
  const std::vector<float> pixels(16 * 8 * 4, 0.5f);
  writeImage(good, 16, 8, {"R", "G", "B", "A"}, pixels, OIIO::TypeDesc::HALF);
  EXPECT_EQ(readColorImage(good).pixels, pixels);
  const std::vector<char> bytes = fileBytes(good);

  // Four channels of one-letter names: 4 x (2 + 16) bytes and the empty name, 73.
  std::vector<char> shortList = bytes;
  putInt32(&shortList, attributeSizeOffset(shortList, "channels", "chlist"), 73 - 18);
  writeBytes(directory_ / "short_channel_list.exr", shortList);
  expectRefused(directory_ / "short_channel_list.exr", "channel list \"channels\" claims 55 bytes");

  // A string list whose one string claims 1 GB: OpenEXR allocates it before it reads it.
  std::vector<char> stringList = bytes;
  const std::string attribute = std::string("views") + '\0' + "stringvector" + '\0';
  std::vector<char> inserted(attribute.begin(), attribute.end());
  for (const std::int32_t value : {8, 1 << 30, 0x41414141})  // size 8: one length and four bytes
    for (int i = 0; i < 4; ++i)
      inserted.push_back(char((std::uint32_t(value) >> (8 * i)) & 0xff));
  stringList.insert(stringList.begin() + 8, inserted.begin(), inserted.end());  // the first attribute
  writeBytes(directory_ / "string_list.exr", stringList);
  expectRefused(directory_ / "string_list.exr", "string list \"views\" holds a string of 1073741824 bytes");

  std::vector<char> longBox = bytes;
  putInt32(&longBox, attributeSizeOffset(longBox, "dataWindow", "box2i"), 20);
  writeBytes(directory_ / "long_box.exr", longBox);
  expectRefused(directory_ / "long_box.exr", "\"dataWindow\" of type box2i claims 20 bytes");
}

// OpenEXR's parts: depth in the first, colour in the second, which is tiled and stored as half (as a
// compositor writing several views or passes would); each is found in its own part.
TEST_F(ImageFilesTest, ReadsColourAndDepthFromDifferentPartsOfATiledHalfExr) {
  const int width = 37, height = 21;  // not a multiple of the tiles
  std::vector<OIIO::ImageSpec> specs(2);
  specs[0] = OIIO::ImageSpec(width, height, 1, OIIO::TypeFloat);
  specs[0].channelnames = {"depth.Z"};
  specs[1] = OIIO::ImageSpec(width, height, 4, OIIO::TypeHalf);
  specs[1].channelnames = {"R", "G", "B", "A"};
  // Both tiled: OpenImageIO 2.4 cannot append a tiled part to a scanline one.
  for (OIIO::ImageSpec& spec : specs)
    spec.tile_width = spec.tile_height = 16;
  std::vector<float> depth(std::size_t(width) * height), color(std::size_t(width) * height * 4);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      depth[std::size_t(y) * width + x] = 1.0f + 0.25f * float(x + y);
      for (int c = 0; c < 4; ++c)
        color[(std::size_t(y) * width + x) * 4 + c] = float(c * 64 + (x + y) % 50);  // exact in half
    }
  }
  const std::filesystem::path path = directory_ / "parts.exr";
  std::unique_ptr<OIIO::ImageOutput> output = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(output && output->supports("multiimage"));
  ASSERT_TRUE(output->open(path.string(), 2, specs.data())) << output->geterror();
  ASSERT_TRUE(output->write_image(OIIO::TypeFloat, depth.data()));
  ASSERT_TRUE(output->open(path.string(), specs[1], OIIO::ImageOutput::AppendSubimage)) << output->geterror();
  ASSERT_TRUE(output->write_image(OIIO::TypeFloat, color.data()));
  ASSERT_TRUE(output->close());

  const FloatImage image = readColorImage(path);
  ASSERT_EQ(image.width, width);
  ASSERT_EQ(image.height, height);
  ASSERT_EQ(image.channels, 4);
  EXPECT_EQ(image.pixels, color);
  const std::optional<FloatImage> readDepth = readDepthImage(path);
  ASSERT_TRUE(readDepth);
  EXPECT_EQ(readDepth->pixels, depth);
}

// OpenImageIO's resample() (which resizeImage once called) is the reference: one sample per destination
// pixel centre, bilinear with edges repeated, or the pixel the centre falls in.
TEST(ImageFilesResize, SamplesAsOpenImageIOsResampleDoes) {
  FloatImage image;
  image.width = 7;
  image.height = 5;
  image.channels = 3;
  for (int i = 0; i < image.width * image.height * image.channels; ++i)
    image.pixels.push_back(std::sin(float(i) * 1.7f) * 10.0f);
  OIIO::ImageBuf source(OIIO::ImageSpec(image.width, image.height, image.channels, OIIO::TypeFloat));
  source.set_pixels(OIIO::ROI::All(), OIIO::TypeFloat, image.pixels.data());
  for (const auto& [width, height] :
       std::vector<std::pair<int, int>>{{13, 9}, {3, 2}, {7, 11}, {1, 1}, {16, 5}}) {
    for (const bool nearest : {false, true}) {
      OIIO::ImageBuf reference(OIIO::ImageSpec(width, height, image.channels, OIIO::TypeFloat));
      ASSERT_TRUE(OIIO::ImageBufAlgo::resample(reference, source, /*interpolate=*/!nearest));
      std::vector<float> expected(std::size_t(width) * height * image.channels);
      reference.get_pixels(OIIO::ROI::All(), OIIO::TypeFloat, expected.data());
      const FloatImage resized = resizeImage(image, width, height, nearest);
      ASSERT_EQ(resized.pixels.size(), expected.size());
      for (std::size_t i = 0; i < expected.size(); ++i)
        ASSERT_NEAR(resized.pixels[i], expected[i], 1e-5f)
            << width << "x" << height << " nearest " << nearest << " at " << i;
    }
  }
}

TEST(ImageFilesResize, NearestRepeatsPixelsAndBilinearBlendsThem) {
  FloatImage image;
  image.width = 2;
  image.height = 1;
  image.channels = 1;
  image.pixels = {0.0f, 1.0f};

  const FloatImage nearest = resizeImage(image, 4, 2, /*nearest=*/true);
  ASSERT_EQ(nearest.width, 4);
  ASSERT_EQ(nearest.height, 2);
  EXPECT_EQ(nearest.pixels, (std::vector<float>{0, 0, 1, 1, 0, 0, 1, 1}));

  // Destination pixel centres fall at source x = 0.25, 0.75, 1.25, 1.75; edges clamp.
  const FloatImage bilinear = resizeImage(image, 4, 1, /*nearest=*/false);
  ASSERT_EQ(bilinear.pixels.size(), 4u);
  EXPECT_FLOAT_EQ(bilinear.pixels[0], 0.0f);
  EXPECT_FLOAT_EQ(bilinear.pixels[1], 0.25f);
  EXPECT_FLOAT_EQ(bilinear.pixels[2], 0.75f);
  EXPECT_FLOAT_EQ(bilinear.pixels[3], 1.0f);
}

TEST(ImageFilesResize, KeepsChannelsAndRejectsBadSizes) {
  FloatImage image;
  image.width = 1;
  image.height = 1;
  image.channels = 4;
  image.pixels = {0.1f, 0.2f, 0.3f, 0.4f};
  const FloatImage larger = resizeImage(image, 3, 2, /*nearest=*/false);
  ASSERT_EQ(larger.channels, 4);
  for (int pixel = 0; pixel < 6; ++pixel)
    EXPECT_FLOAT_EQ(larger.pixels[pixel * 4 + 2], 0.3f);
  EXPECT_EQ(resizeImage(image, 1, 1, true).pixels, image.pixels);
  EXPECT_THROW(resizeImage(image, 0, 5, true), Error);
  image.pixels.pop_back();
  EXPECT_THROW(resizeImage(image, 2, 2, true), Error);
}

}  // namespace
}  // namespace spindrift
