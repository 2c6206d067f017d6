// End to end: the `spindrift` command on a scene written here, its EXR read back with OpenImageIO.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "CliCommand.h"
#include "TempDirectory.h"

namespace {

// Eight particles around the origin, one of them NaN, seen by a camera on -Y.
std::filesystem::path writeScene(const TempDirectory& directory, const std::string& extra = "") {
  directory.write(
      "particles.ply",
      "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
      "end_header\n0 0 0\n0.3 0 0\n-0.3 0 0\n0 0 0.3\n0 0 -0.3\n0.2 0.2 0.2\n-0.2 -0.2 0.1\nnan 0 0\n");
  return directory.write("scene.json", R"({"version": 1, "frame": 3,
      "camera": {"width": 64, "height": 48, "fov_y_deg": 40, "position": [0, -3, 0], "target": [0, 0, 0],
                 "up": [0, 0, 1]},
      "particles": [{"path": "particles.ply", "radius": 0.2}],
      "background": {"color": [0.2, 0.3, 0.4]})" +
                                           extra + "}");
}

}  // namespace

TEST(CLI, RendersExrPngAndStats) {
  TempDirectory directory;
  const std::filesystem::path scene = writeScene(directory);
  const auto exr = directory.path() / "out.exr", png = directory.path() / "out.png",
             stats = directory.path() / "stats.json";
  const CommandResult result = runCli("render " + scene.string() + " -o " + exr.string() + " --png " +
                                      png.string() + " --stats " + stats.string());
  ASSERT_EQ(result.exitCode, 0) << result.stderrText;
  EXPECT_TRUE(std::filesystem::exists(png));

  auto input = OIIO::ImageInput::open(exr.string());
  ASSERT_TRUE(input) << OIIO::geterror();
  const OIIO::ImageSpec spec = input->spec();
  EXPECT_EQ(spec.width, 64);
  EXPECT_EQ(spec.height, 48);
  const std::set<std::string> channels(spec.channelnames.begin(), spec.channelnames.end());
  std::set<std::string> expected{"composite.R",     "composite.G",     "composite.B",     "composite.A",
                                 "liquid.R",        "liquid.G",        "liquid.B",        "liquid.A",
                                 "depth.Z",         "normal.X",        "normal.Y",        "normal.Z",
                                 "liquid_splash.R", "liquid_splash.G", "liquid_splash.B", "liquid_splash.A",
                                 "liquid_class.Y",  "thickness.Y"};
  for (const char* layer : {"foam", "foam_spray", "foam_surface", "foam_bubble"})
    for (const char* channel : {".R", ".G", ".B", ".A"})
      expected.insert(std::string(layer) + channel);
  for (const char* layer : {"foam_shadow", "foam_irradiance", "refraction_uv", "transmittance", "reflection"})
    for (const char* channel : {".R", ".G", ".B"})
      expected.insert(std::string(layer) + channel);
  expected.insert("foam_thickness.Y");
  EXPECT_EQ(channels, expected);
  std::vector<float> pixels(std::size_t(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
  std::size_t nonFinite = 0;
  for (float value : pixels)
    nonFinite += !std::isfinite(value);
  EXPECT_EQ(nonFinite, 0u);

  nlohmann::json json;
  std::ifstream(stats) >> json;
  EXPECT_EQ(json["frame"], 3) << "the scene's `frame` is the default";
  EXPECT_EQ(json["particles"]["liquid"], 7);
  EXPECT_EQ(json["particles"]["dropped_invalid"], 1);
  std::vector<std::string> passes;
  for (const auto& pass : json["passes"])
    passes.push_back(pass["name"]);
  EXPECT_EQ(passes.front(), "background");
  EXPECT_EQ(passes.back(), "composite");
  EXPECT_NE(std::find(passes.begin(), passes.end(), "refraction"), passes.end());
  EXPECT_FALSE(json["gl_renderer"].get<std::string>().empty());
}

// --exr-compression and --exr-half reach the file: its header names the compression, colour channels are
// half and depth stays float, and the pixels are those of the default float ZIP file (to half's precision).
TEST(CLI, ExrCompressionAndHalfColourReachTheFile) {
  TempDirectory directory;
  const std::filesystem::path scene = writeScene(directory);
  const auto plain = directory.path() / "plain.exr", small = directory.path() / "small.exr";
  ASSERT_EQ(runCli("render " + scene.string() + " -q -o " + plain.string()).exitCode, 0);
  const CommandResult result =
      runCli("render " + scene.string() + " -q --exr-compression piz --exr-half -o " + small.string());
  ASSERT_EQ(result.exitCode, 0) << result.stderrText;

  auto read = [](const std::filesystem::path& path, OIIO::ImageSpec& spec) {
    auto input = OIIO::ImageInput::open(path.string());
    EXPECT_TRUE(input) << OIIO::geterror();
    spec = input->spec();
    std::vector<float> pixels(std::size_t(spec.width) * spec.height * spec.nchannels);
    EXPECT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    return pixels;
  };
  OIIO::ImageSpec plainSpec, smallSpec;
  const std::vector<float> plainPixels = read(plain, plainSpec), smallPixels = read(small, smallSpec);
  EXPECT_EQ(plainSpec.get_string_attribute("compression"), "zip") << "the default, zip:1";
  EXPECT_EQ(smallSpec.get_string_attribute("compression"), "piz");
  ASSERT_EQ(plainSpec.channelnames, smallSpec.channelnames);
  for (int c = 0; c < smallSpec.nchannels; ++c) {
    const std::string& name = smallSpec.channelnames[std::size_t(c)];
    const bool keepsFloat = name == "depth.Z" || name.rfind("refraction_uv.", 0) == 0;
    EXPECT_EQ(smallSpec.channelformat(c), keepsFloat ? OIIO::TypeFloat : OIIO::TypeHalf) << name;
    EXPECT_EQ(plainSpec.channelformat(c), OIIO::TypeFloat) << name;
  }
  std::size_t differ = 0;
  for (std::size_t i = 0; i < plainPixels.size(); ++i) {
    ASSERT_TRUE(std::isfinite(smallPixels[i]));
    differ += std::abs(smallPixels[i] - plainPixels[i]) > 1e-3f * std::max(1.0f, std::abs(plainPixels[i]));
  }
  EXPECT_EQ(differ, 0u) << "half keeps 11 bits of mantissa";

  const CommandResult misspelt = runCli("render " + scene.string() + " --exr-compression zpi -o x.exr");
  EXPECT_EQ(misspelt.exitCode, 2) << "an unknown compression is a usage error";
  for (const char* level : {"zip:0", "piz:3"})
    EXPECT_EQ(runCli("render " + scene.string() + " --exr-compression " + level + " -o x.exr").exitCode, 2)
        << level;
}

TEST(CLI, SequenceWritesOneFilePerFrame) {
  TempDirectory directory;
  const std::filesystem::path scene = writeScene(directory);
  const CommandResult result = runCli("render " + scene.string() + " --frames 4-6 -q -o " +
                                      (directory.path() / "frame_####.exr").string());
  ASSERT_EQ(result.exitCode, 0) << result.stderrText;
  for (const char* name : {"frame_0004.exr", "frame_0005.exr", "frame_0006.exr"})
    EXPECT_TRUE(std::filesystem::exists(directory.path() / name)) << name;
}

TEST(CLI, BadSceneIsOneErrorLineAndExitCodeOne) {
  TempDirectory directory;
  const std::filesystem::path scene = writeScene(directory, R"(, "liquid": {"ior": 5})");
  const auto exr = directory.path() / "out.exr";
  const CommandResult result = runCli("render " + scene.string() + " -o " + exr.string());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.stderrText.find("liquid.ior"), std::string::npos) << result.stderrText;
  EXPECT_FALSE(std::filesystem::exists(exr)) << "a failed render leaves no output";
}

TEST(CLI, UsageErrorsExitWithTwo) {
  EXPECT_EQ(runCli("render").exitCode, 2);
  EXPECT_EQ(runCli("render scene.json --frames 9-3 -o x.exr").exitCode, 2);
  EXPECT_EQ(runCli("frobnicate").exitCode, 2);
}

TEST(CLI, SeveralFramesNeedAFramePatternInTheOutput) {
  TempDirectory directory;
  const std::filesystem::path scene = writeScene(directory);
  const CommandResult result =
      runCli("render " + scene.string() + " --frames 1-2 -o " + (directory.path() / "x.exr").string());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.stderrText.find("####"), std::string::npos) << result.stderrText;
}

// With no usable EGL vendor there is no OpenGL: one clear line and exit code 1, never a crash.
TEST(CLI, NoOpenGLIsAClearErrorNotACrash) {
  const CommandResult result = runCli("info", "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/egl_vendor.json");
  EXPECT_EQ(result.exitCode, 1) << result.stderrText;
  EXPECT_NE(result.stderrText.find("no OpenGL 4.5 context"), std::string::npos) << result.stderrText;
}

TEST(CLI, ParamsMarkdownIsTheParameterTable) {
  const CommandResult result = runCli("params --markdown > /dev/null");
  EXPECT_EQ(result.exitCode, 0);
}

namespace {

// Every channel of an EXR by name.
std::map<std::string, std::vector<float>> readChannels(const std::filesystem::path& path) {
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) return {};
  const OIIO::ImageSpec spec = input->spec();
  std::vector<float> pixels(std::size_t(spec.width) * spec.height * spec.nchannels);
  input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  std::map<std::string, std::vector<float>> channels;
  for (int c = 0; c < spec.nchannels; ++c)
    for (std::size_t i = c; i < pixels.size(); i += std::size_t(spec.nchannels))
      channels[spec.channelnames[c]].push_back(pixels[i]);
  return channels;
}

}  // namespace

// The reduced pipeline (--layers depth,normal: no foam, no composite) writes exactly the chosen layers, and
// they equal the full pipeline's.
TEST(CLI, LayersChooseWhatIsComputedAndWrittenAndMatchTheFullPipeline) {
  TempDirectory directory;
  const std::filesystem::path scene = writeScene(directory);
  const auto full = directory.path() / "full.exr", reduced = directory.path() / "reduced.exr",
             stats = directory.path() / "stats.json";
  ASSERT_EQ(runCli("render -q " + scene.string() + " -o " + full.string()).exitCode, 0);
  const CommandResult result = runCli("render -q " + scene.string() + " -o " + reduced.string() +
                                      " --layers depth,normal --stats " + stats.string());
  ASSERT_EQ(result.exitCode, 0) << result.stderrText;
  const auto fullChannels = readChannels(full), reducedChannels = readChannels(reduced);
  std::set<std::string> names;
  for (const auto& [name, values] : reducedChannels)
    names.insert(name);
  EXPECT_EQ(names, (std::set<std::string>{"depth.Z", "normal.X", "normal.Y", "normal.Z"}));
  std::size_t covered = 0;
  for (const auto& [name, values] : reducedChannels) {
    ASSERT_EQ(values, fullChannels.at(name)) << name;
    for (float value : values)
      EXPECT_TRUE(std::isfinite(value)) << name;
  }
  for (float depth : reducedChannels.at("depth.Z"))
    covered += depth < 1e9f;
  EXPECT_GT(covered, 0u) << "the scene shows liquid";
  const nlohmann::json json = nlohmann::json::parse(std::ifstream(stats));
  std::set<std::string> skipped;
  for (const auto& pass : json["skipped"])
    skipped.insert(pass["name"].get<std::string>());
  EXPECT_TRUE(skipped.count("composite"));
}

TEST(CLI, UnknownLayerIsOneErrorLine) {
  TempDirectory directory;
  const std::filesystem::path scene = writeScene(directory);
  const CommandResult result = runCli("render -q " + scene.string() + " --layers depth,colour -o " +
                                      (directory.path() / "x.exr").string());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.stderrText.find("unknown layer \"colour\""), std::string::npos) << result.stderrText;
}

// The CLI maps the first frame's heap at once while its renderer starts (cli/Heap.cpp): the frame then takes
// its targets, readback and preparation from pages already mapped, and the stats say how much was mapped
// (and with huge pages, where the kernel gives them) and how many pages the frame faulted in. The count is
// the kernel's, not a time: with the heap mapped the frame must fault in fewer than half the pages it does
// without (a 400×300 frame: 24,900 without, 420 with, on the project's VM).
TEST(CLI, TheFirstFramesHeapIsMappedBeforeItAndItsPagesNeedNotFaultIn) {
  TempDirectory directory;
  std::string scene = writeScene(directory).string();
  {
    nlohmann::json description;
    std::ifstream(scene) >> description;
    description["camera"]["width"] = 400;
    description["camera"]["height"] = 300;
    std::ofstream(scene) << description.dump();
  }
  auto render = [&](const std::string& name, const std::string& options) {
    const auto stats = directory.path() / (name + ".json");
    const CommandResult result = runCli("render -q " + scene + " --frames 3,3 -o " +
                                        (directory.path() / (name + "_####.exr")).string() + " --stats " +
                                        stats.string() + " " + options);
    EXPECT_EQ(result.exitCode, 0) << result.stderrText;
    nlohmann::json frames;
    std::ifstream(stats) >> frames;
    EXPECT_FALSE(frames["frames"][1]["process"].contains("heap")) << "the heap is mapped for the first frame";
    return frames["frames"][0];
  };
  const nlohmann::json mapped = render("mapped", "");
  const nlohmann::json faulted = render("faulted", "--no-populate-heap");
  ASSERT_TRUE(mapped.contains("process") && faulted.contains("process"));
  EXPECT_EQ(faulted["process"]["heap"]["populated"], false);
  EXPECT_EQ(faulted["process"]["heap"]["why_not"], "--no-populate-heap");
  const nlohmann::json& heap = mapped["process"]["heap"];
  if (!heap["populated"].get<bool>()) GTEST_SKIP() << "the heap was not mapped: " << heap.dump();
  // 128 MiB and 700 bytes a pixel, in blocks of 16 MiB whose partial first and last pages stay unmapped.
  const double expectedMib = 128.0 + 700.0 * 400 * 300 / (1 << 20);
  EXPECT_GT(heap["populated_mib"].get<double>(), expectedMib - 1.0);
  EXPECT_LE(heap["populated_mib"].get<double>(), expectedMib);
  // The heap asks for transparent huge pages: where the kernel gives them on request, most of it is mapped
  // with them (212 of 214 MiB at 480×270 on the project's VM); where it never does, none is.
  const std::string hugePages = heap["transparent_huge_pages"];
  const double hugePageMib = heap["huge_page_mib"];
  if (hugePages == "always" || hugePages == "madvise")
    EXPECT_GT(hugePageMib, 0.5 * expectedMib) << heap.dump();
  else
    EXPECT_EQ(hugePageMib, 0.0) << heap.dump();  // "never", or a kernel without them ("unknown")
  const long withMapping = mapped["process"]["page_faults"], without = faulted["process"]["page_faults"];
  EXPECT_GE(withMapping, 0);
  EXPECT_GT(mapped["process"]["user_ms"].get<double>(), 0.0) << "the frame's CPU time, every thread's";
  EXPECT_GE(mapped["process"]["system_ms"].get<double>(), 0.0);
  EXPECT_LT(2 * withMapping, without) << "with the heap mapped " << withMapping << ", without " << without;
}
