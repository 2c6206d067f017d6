// The same scene gives the same bits: twice in one process, from two processes, and with one worker thread
// instead of all (the CPU preparation's parallel loops must not depend on scheduling). A farm relies on it:
// a frame rerendered on another node after a requeue must match its neighbours exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include <glm/geometric.hpp>

#include "CliCommand.h"
#include "TempDirectory.h"
#include "spindrift/Output.h"
#include "spindrift/Renderer.h"

namespace {

// 40,000 liquid particles in a noisy slab with a crest (several of the preparation's 16,384-particle blocks,
// splashes and aggregates both), as binary PLY, and the same file again as spray.
std::filesystem::path writeDeterminismScene(const TempDirectory& directory) {
  constexpr int kCount = 40000;
  std::mt19937 random(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::string body;
  for (int i = 0; i < kCount; ++i) {
    const float x = unit(random) * 2.0f - 1.0f, y = unit(random) * 2.0f - 1.0f;
    const float z = unit(random) * 0.3f + 0.4f * std::exp(-8.0f * (x * x + y * y)) * unit(random);
    const float xyz[3] = {x, y, z};
    body.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  }
  directory.write("p.ply", "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(kCount) +
                               "\nproperty float x\nproperty float y\nproperty float z\nend_header\n" + body);
  return directory.write("scene.json", R"({"version": 1,
      "camera": {"width": 160, "height": 120, "fov_y_deg": 40, "position": [0, -4, 2], "target": [0, 0, 0.2],
                 "up": [0, 0, 1]},
      "particles": [{"path": "p.ply", "radius": 0.03},
                    {"path": "p.ply", "radius": 0.01, "role": "foam", "kind": "spray",
                     "world_from_file": [1,0,0,0, 0,1,0,0, 0,0,1,0.5, 0,0,0,1]}],
      "background": {"color": [0.2, 0.3, 0.4]}})");
}

std::string readBytes(const std::filesystem::path& path) {
  std::ifstream stream(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST(Determinism, SameProcessTwiceGivesIdenticalLayersAndFiles) {
  TempDirectory directory;
  const spindrift::Scene scene = spindrift::loadScene(writeDeterminismScene(directory));
  spindrift::Renderer renderer;
  const spindrift::RenderResult first = renderer.renderFrame(scene, 1);
  const spindrift::RenderResult second = renderer.renderFrame(scene, 1);
  const spindrift::RenderResult third = renderer.renderFrame(scene, 1);  // with the second's shapes
  ASSERT_EQ(first.layers.size(), second.layers.size());
  ASSERT_EQ(first.layers.size(), third.layers.size());
  std::size_t liquidPixels = 0;
  for (std::size_t i = 0; i < first.layers.size(); ++i) {
    const auto& a = first.layers[i].pixels;
    const auto& b = second.layers[i].pixels;
    const auto& c = third.layers[i].pixels;
    ASSERT_EQ(a.size(), b.size()) << first.layers[i].name;
    ASSERT_EQ(a.size(), c.size()) << first.layers[i].name;
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << first.layers[i].name;
    EXPECT_EQ(std::memcmp(a.data(), c.data(), a.size() * sizeof(float)), 0) << first.layers[i].name;
    for (float value : a)
      ASSERT_TRUE(std::isfinite(value)) << first.layers[i].name;
    if (first.layers[i].name == "liquid_class")
      for (float value : a)
        liquidPixels += value > 0.0f;
  }
  EXPECT_GT(liquidPixels, 2000u) << "the scene must exercise the liquid";
  // The second frame of the same particles kept its shapes (liquid.reuse_shapes), the third reused them, and
  // all three gave the same bits.
  EXPECT_EQ(first.stats.liquid.shapesNotKept, "no frame before");
  EXPECT_EQ(second.stats.liquid.shapesNotKept,
            "the frame before kept none (the same particles: this frame keeps them)");
  EXPECT_EQ(third.stats.liquid.shapesNotKept, "");
  EXPECT_GT(first.stats.liquid.splashParticles, 0u);
  EXPECT_GT(first.stats.liquid.aggregateParticles, 16384u);
  spindrift::writeExr(first, directory.path() / "a.exr");
  spindrift::writeExr(second, directory.path() / "b.exr");
  EXPECT_EQ(readBytes(directory.path() / "a.exr"), readBytes(directory.path() / "b.exr"));
}

TEST(Determinism, ACameraMovedOverTheSameParticlesKeepsTheirShapesAndGetsWhatAFreshRendererGets) {
  // A viewport orbiting a paused frame under a sun: the second camera's frame reuses the first's shapes and
  // the sun's view, and must match, bit for bit, that camera rendered by a renderer that never saw the first.
  TempDirectory directory;
  spindrift::Scene scene = spindrift::loadScene(writeDeterminismScene(directory));
  spindrift::Light sun;
  sun.direction = glm::normalize(glm::vec3(0.4f, 0.3f, -1.0f));
  scene.lights.push_back(sun);
  spindrift::Renderer orbiting;
  orbiting.renderFrame(scene, 1);
  orbiting.renderFrame(scene, 1);  // the same particles again: their shapes are kept from here on
  // Turned where it stands: its nearest pixel on the liquid is as large, so the lights' and the sky's views
  // want the sides they had (a camera that moves nearer may want finer ones).
  scene.camera = spindrift::Camera::lookAt(160, 120, 40.0f, {0, -4, 2}, {0.25f, 0.1f, 0.3f}, {0, 0, 1});
  const spindrift::RenderResult moved = orbiting.renderFrame(scene, 1);
  EXPECT_EQ(moved.stats.liquid.shapesNotKept, "");
  EXPECT_EQ(moved.stats.liquid.culled, 0u) << "a view that culls shapes its own cloud: nothing kept to reuse";
  EXPECT_TRUE(moved.stats.light.viewsKept);
  EXPECT_EQ(moved.stats.light.lightsSeeingLiquid, 1u);
  spindrift::Renderer fresh;
  const spindrift::RenderResult alone = fresh.renderFrame(scene, 1);
  EXPECT_EQ(alone.stats.liquid.shapesNotKept, "no frame before");
  EXPECT_FALSE(alone.stats.light.viewsKept);
  ASSERT_EQ(moved.layers.size(), alone.layers.size());
  for (std::size_t i = 0; i < moved.layers.size(); ++i) {
    const auto& a = moved.layers[i].pixels;
    const auto& b = alone.layers[i].pixels;
    ASSERT_EQ(a.size(), b.size()) << moved.layers[i].name;
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << moved.layers[i].name;
  }
  // A changed parameter shapes them anew.
  scene.parameters.liquid.surface_offset += 0.1f;
  EXPECT_EQ(orbiting.renderFrame(scene, 1).stats.liquid.shapesNotKept, "a shaping parameter changed");
}

TEST(Determinism, TwoProcessesAndOneWorkerThreadGiveIdenticalExrs) {
  TempDirectory directory;
  const std::string scene = writeDeterminismScene(directory).string();
  const std::filesystem::path a = directory.path() / "a.exr", b = directory.path() / "b.exr",
                              single = directory.path() / "single.exr";
  ASSERT_EQ(runCli("render " + scene + " -q -o " + a.string()).exitCode, 0);
  ASSERT_EQ(runCli("render " + scene + " -q -o " + b.string()).exitCode, 0);
  const CommandResult oneThread = runCli("render " + scene + " -q --threads 1 -o " + single.string());
  ASSERT_EQ(oneThread.exitCode, 0) << oneThread.stderrText;
  const std::string reference = readBytes(a);
  ASSERT_GT(reference.size(), 1000u);
  EXPECT_EQ(readBytes(b), reference) << "two processes";
  EXPECT_EQ(readBytes(single), reference) << "one worker thread against all";
}
