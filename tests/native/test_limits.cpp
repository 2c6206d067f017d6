// Limits checked before allocating (spindrift/Limits.h): each bad input is a named case whose error names
// the limit, and no case allocates what it is refusing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <OpenImageIO/imageio.h>

#include "TempDirectory.h"
#include "io/ImageFiles.h"
#include "io/ParticleFile.h"
#include "spindrift/Error.h"
#include "spindrift/Limits.h"
#include "spindrift/Renderer.h"

using namespace spindrift;

namespace {

Camera goodCamera() {
  return Camera::lookAt(64, 48, 40.0f, {0, -3, 0}, {0, 0, 0}, {0, 0, 1});
}

std::string cameraError(const Camera& camera) {
  try {
    validateCamera(camera);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

// Sets an explicit memory ceiling for one test.
struct MemoryCeiling {
  explicit MemoryCeiling(std::uint64_t bytes) { setMemoryLimitBytes(bytes); }
  ~MemoryCeiling() { setMemoryLimitBytes(0); }
};

}  // namespace

TEST(Limits, AGoodCameraPasses) {
  EXPECT_EQ(cameraError(goodCamera()), "");
}

TEST(Limits, CameraFovOfZeroOr180IsRejected) {
  for (float fov : {0.0f, -10.0f, 180.0f, 270.0f, std::nanf("")}) {
    Camera camera = goodCamera();
    camera.fovYDegrees = fov;
    EXPECT_NE(cameraError(camera).find("fov_y_deg"), std::string::npos) << fov;
  }
}

TEST(Limits, CameraNearMustBePositiveAndBeforeFar) {
  Camera camera = goodCamera();
  camera.nearClip = 0.0f;
  EXPECT_NE(cameraError(camera).find("near 0 must be finite and > 0"), std::string::npos)
      << cameraError(camera);
  camera.nearClip = 5.0f;
  camera.farClip = 5.0f;
  EXPECT_NE(cameraError(camera).find("far 5 must be finite and > near (5)"), std::string::npos)
      << cameraError(camera);
  camera.farClip = INFINITY;
  EXPECT_NE(cameraError(camera).find("far"), std::string::npos);
}

TEST(Limits, CameraMatrixMustBeFiniteAffineAndInvertible) {
  Camera camera = goodCamera();
  camera.worldFromCamera[3][1] = NAN;
  EXPECT_NE(cameraError(camera).find("non-finite element (row 1, column 3)"), std::string::npos)
      << cameraError(camera);
  camera = goodCamera();
  camera.worldFromCamera[2][3] = 1.0f;
  EXPECT_NE(cameraError(camera).find("affine"), std::string::npos);
  camera = goodCamera();
  camera.worldFromCamera[0] = glm::vec4(0.0f);
  EXPECT_NE(cameraError(camera).find("singular"), std::string::npos);
}

TEST(Limits, ImageSidesOutsideOneTo16384AreRejected) {
  for (auto [width, height] : {std::pair{0, 10}, std::pair{10, -1}, std::pair{16385, 10}}) {
    Camera camera = goodCamera();
    camera.width = width;
    camera.height = height;
    EXPECT_NE(cameraError(camera).find("[1, 16384]"), std::string::npos) << width << "x" << height;
  }
}

TEST(Limits, ParticleArraysOfMismatchedLengthsOrBadRadiiAreRejected) {
  Particles particles;
  particles.append({0, 0, 0}, 0.1f, ParticleKind::Liquid, 0.0f, {0, 0, 0});
  particles.append({1, 0, 0}, 0.1f, ParticleKind::Liquid, 0.0f, {0, 0, 0});
  EXPECT_NO_THROW(validateParticles(particles));
  Particles shortRadii = particles;
  shortRadii.radii.pop_back();
  EXPECT_THROW(validateParticles(shortRadii), Error);
  try {
    validateParticles(shortRadii);
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "particles: radii has 1 entries, positions 2");
  }
  for (float radius : {0.0f, -0.5f, INFINITY, NAN}) {
    Particles bad = particles;
    bad.radii[1] = radius;
    EXPECT_THROW(validateParticles(bad), Error) << radius;
  }
  Particles nonFinite = particles;
  nonFinite.positions[0].y = -INFINITY;
  EXPECT_THROW(validateParticles(nonFinite), Error);
}

TEST(Limits, ImagesBeyondTheGlLimitsNameTheLimit) {
  GlLimits limits;
  limits.maxTextureSize = 8192;
  limits.maxViewportWidth = limits.maxViewportHeight = 16384;
  limits.maxFramebufferWidth = limits.maxFramebufferHeight = 16384;
  EXPECT_NO_THROW(checkImageFitsGl(limits, 8192, 100, "camera: the image"));
  try {
    checkImageFitsGl(limits, 8193, 100, "camera: the image");
    FAIL() << "accepted an image wider than GL_MAX_TEXTURE_SIZE";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("GL_MAX_TEXTURE_SIZE 8192"), std::string::npos) << error.what();
  }
}

TEST(Limits, TheRendererKnowsItsGlLimits) {
  Renderer renderer;
  EXPECT_GE(renderer.glLimits().maxTextureSize, 1024);  // OpenGL 4.5's minimum is 16384; llvmpipe reports it
  EXPECT_GE(renderer.glLimits().maxImageWidth(), 1024);
  EXPECT_GE(renderer.glLimits().maxImageHeight(), 1024);
}

TEST(Limits, AFrameLargerThanTheMemoryAvailableIsRefusedBeforeRendering) {
  Renderer renderer;
  Scene scene;
  scene.camera = Camera::lookAt(4000, 4000, 40.0f, {0, -3, 0}, {0, 0, 0}, {0, 0, 1});
  MemoryCeiling ceiling(std::uint64_t(64) << 20);
  try {
    renderer.renderParticles(scene, Particles{}, 1);
    FAIL() << "rendered a frame needing ~15 GiB under a 64 MiB ceiling";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(
        message.find("a 4000x4000 frame of 0 particles needs 15625 MiB, more than the 64 MiB available"),
        std::string::npos)
        << message;
  }
}

TEST(Limits, MemoryAvailableIsPositiveAndFollowsTheCeiling) {
  EXPECT_GT(availableMemoryBytes(), std::uint64_t(16) << 20);
  MemoryCeiling ceiling(std::uint64_t(1) << 20);
  EXPECT_EQ(availableMemoryBytes(), std::uint64_t(1) << 20);
  EXPECT_THROW(requireMemory(std::uint64_t(2) << 20, "two MiB"), Error);
  EXPECT_NO_THROW(requireMemory(std::uint64_t(1) << 19, "half a MiB"));
}

TEST(Limits, AnImageWhoseHeaderClaimsTooMuchIsRefusedBeforeReading) {
  TempDirectory directory;
  // A valid 2000x2000 EXR: its pixels need 61 MiB as float RGBA, more than the ceiling below.
  const std::filesystem::path path = directory.path() / "big.exr";
  {
    auto output = OIIO::ImageOutput::create(path.string());
    OIIO::ImageSpec spec(2000, 2000, 4, OIIO::TypeDesc::HALF);
    ASSERT_TRUE(output->open(path.string(), spec));
    std::vector<float> pixels(std::size_t(2000) * 2000 * 4, 0.5f);
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    output->close();
  }
  MemoryCeiling ceiling(std::uint64_t(32) << 20);
  try {
    readColorImage(path);
    FAIL() << "read an image larger than the memory ceiling";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("big.exr: a 2000x2000 image needs"), std::string::npos)
        << error.what();
  }
}

TEST(Limits, APlyWhoseVerticesExceedMemoryIsRefused) {
  TempDirectory directory;
  std::string body;
  for (int i = 0; i < 100000; ++i)
    body += "0 0 0\n";
  const auto path = directory.write("many.ply",
                                    "ply\nformat ascii 1.0\nelement vertex 100000\nproperty float x\n"
                                    "property float y\nproperty float z\nend_header\n" +
                                        body);
  MemoryCeiling ceiling(std::uint64_t(2) << 20);
  try {
    readPly(path);
    FAIL() << "read 100,000 vertices under a 2 MiB ceiling";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("the vertex arrays needs 3 MiB"), std::string::npos)
        << error.what();
  }
}
