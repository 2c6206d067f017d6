// GL tests: repeated renders in one process must not grow GL objects or resident memory.
#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>
#include <random>

#include "TempDirectory.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Error.h"
#include "spindrift/Renderer.h"

using namespace spindrift;

namespace {

long residentKilobytes() {
  std::ifstream statm("/proc/self/statm");
  long sizePages = 0, residentPages = 0;
  statm >> sizePages >> residentPages;
  return residentPages * (sysconf(_SC_PAGESIZE) / 1024);
}

std::array<long, std::size_t(GlObjectType::Count)> liveObjects() {
  std::array<long, std::size_t(GlObjectType::Count)> counts{};
  for (std::size_t i = 0; i < counts.size(); ++i)
    counts[i] = liveGlObjectCount(GlObjectType(i));
  return counts;
}

Particles randomParticles(std::mt19937& random, int count) {
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
  Particles particles;
  // Every fourth particle is foam, so the foam passes run (and must not leak) too.
  const ParticleKind kinds[] = {ParticleKind::Liquid, ParticleKind::Liquid, ParticleKind::Liquid,
                                ParticleKind::Spray,  ParticleKind::Liquid, ParticleKind::Liquid,
                                ParticleKind::Liquid, ParticleKind::Foam,   ParticleKind::Liquid,
                                ParticleKind::Liquid, ParticleKind::Liquid, ParticleKind::Bubble};
  for (int i = 0; i < count; ++i)
    particles.append({coordinate(random), coordinate(random), coordinate(random)}, 0.05f, kinds[i % 12], 0.0f,
                     glm::vec3(0.0f));
  return particles;
}

}  // namespace

TEST(GLResources, TwoHundredFramesKeepObjectsAndMemoryFlat) {
  Scene scene;
  scene.camera = Camera::lookAt(96, 64, 45.0f, {0, -4, 1}, {0, 0, 0}, {0, 0, 1});
  Renderer renderer;
  std::mt19937 random(7);
  std::array<long, std::size_t(GlObjectType::Count)> afterWarmUp{};
  long residentAfterWarmUp = 0;
  for (int frame = 1; frame <= 200; ++frame) {
    // Particle counts vary from frame to frame, and every tenth frame is empty, as in a real sequence.
    const int count = frame % 10 == 0 ? 0 : 200 + int(random() % 800);
    const RenderResult result = renderer.renderParticles(scene, randomParticles(random, count), frame);
    ASSERT_EQ(result.layers.size(), 17u);  // 10 of the liquid and composite, 7 of the foam
    if (frame == 20) {
      afterWarmUp = liveObjects();
      residentAfterWarmUp = residentKilobytes();
    }
  }
  EXPECT_EQ(liveObjects(), afterWarmUp);
  const long growth = residentKilobytes() - residentAfterWarmUp;
  EXPECT_LT(growth, 8 * 1024) << "resident memory grew by " << growth << " KiB over 180 frames";
}

TEST(GLResources, RenderersReleaseEverythingTheyMade) {
  const auto before = liveObjects();
  for (int i = 0; i < 3; ++i) {
    Scene scene;
    scene.camera = Camera::lookAt(32, 32, 45.0f, {0, -4, 0}, {0, 0, 0}, {0, 0, 1});
    Renderer renderer;
    Particles particles;
    particles.append({0, 0, 0}, 0.5f, ParticleKind::Liquid, 0.0f, glm::vec3(0));
    renderer.renderParticles(scene, particles, 1);
  }
  EXPECT_EQ(liveObjects(), before);
}

TEST(GLResources, ErrorsInsideAFrameReachTheCallerAndTheRendererGoesOn) {
  Renderer renderer;
  Scene scene;
  scene.camera = Camera::lookAt(32, 32, 45.0f, {0, -4, 0}, {0, 0, 0}, {0, 0, 1});
  scene.background.image = "/nonexistent/background.exr";
  Particles particles;
  particles.append({0, 0, 0}, 0.5f, ParticleKind::Liquid, 0.0f, glm::vec3(0));
  EXPECT_THROW(renderer.renderParticles(scene, particles, 1), Error);
  scene.background.image.clear();
  EXPECT_NO_THROW(renderer.renderParticles(scene, particles, 1));
}

// The programs are built on the GL thread while the caller goes on (the first frame's loading and
// preparation): a Renderer dropped before they are done waits for them and releases them.
TEST(GLResources, ARendererDroppedWhileItsProgramsBuildReleasesEverything) {
  const auto before = liveObjects();
  for (int i = 0; i < 3; ++i) {
    Renderer renderer;
  }
  EXPECT_EQ(liveObjects(), before);
}

// A shader directory that the construction's check accepts but whose programs cannot be built: every frame
// reports the build's Error, and the Renderer's destruction is clean.
TEST(GLResources, ProgramsThatCannotBeBuiltFailEveryFrameWithTheirError) {
  TempDirectory directory;
  std::filesystem::copy_file(findShaderDirectory() / "fullscreen.vert", directory.path() / "fullscreen.vert");
  Renderer renderer(directory.path());
  Scene scene;
  scene.camera = Camera::lookAt(32, 32, 45.0f, {0, -4, 0}, {0, 0, 0}, {0, 0, 1});
  Particles particles;
  particles.append({0, 0, 0}, 0.5f, ParticleKind::Liquid, 0.0f, glm::vec3(0));
  for (int frame = 1; frame <= 2; ++frame) {
    try {
      renderer.renderParticles(scene, particles, frame);
      ADD_FAILURE() << "frame " << frame << " rendered without its programs";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("cannot read shader"), std::string::npos) << error.what();
    }
  }
}

TEST(GLResources, ARendererWithoutShadersFailsWhenMade) {
  TempDirectory empty;
  try {
    Renderer renderer(empty.path());
    ADD_FAILURE() << "a Renderer was made without shaders";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("cannot read shader"), std::string::npos) << error.what();
  }
}
