#include "spindrift/Limits.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include <glm/gtc/matrix_access.hpp>
#include <glm/mat3x3.hpp>

#include "spindrift/Error.h"

namespace spindrift {
namespace {

constexpr int kMaximumImageSide = 16384;
std::atomic<std::uint64_t> explicitLimit{0};

std::string number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// MemAvailable from /proc/meminfo in bytes, or the largest value when unknown (not Linux).
std::uint64_t memAvailable() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kibibytes = 0;
  std::string unit;
  while (meminfo >> key >> kibibytes >> unit)
    if (key == "MemAvailable:") return kibibytes * 1024;
  return std::numeric_limits<std::uint64_t>::max();
}

// What is left under a cgroup v2 memory limit (a Slurm job, a container), or the largest value when none.
std::uint64_t cgroupHeadroom() {
  std::ifstream self("/proc/self/cgroup");
  std::string line;
  while (std::getline(self, line)) {
    if (line.rfind("0::", 0) != 0) continue;
    const std::string directory = "/sys/fs/cgroup" + line.substr(3);
    std::ifstream maxFile(directory + "/memory.max"), currentFile(directory + "/memory.current");
    std::string maxText;
    std::uint64_t current = 0;
    if (!(maxFile >> maxText) || maxText == "max" || !(currentFile >> current)) break;
    const std::uint64_t maximum = std::stoull(maxText);
    return maximum > current ? maximum - current : 0;
  }
  return std::numeric_limits<std::uint64_t>::max();
}

}  // namespace

int GlLimits::maxImageWidth() const {
  return std::min({maxTextureSize, maxViewportWidth, maxFramebufferWidth});
}
int GlLimits::maxImageHeight() const {
  return std::min({maxTextureSize, maxViewportHeight, maxFramebufferHeight});
}

void validateCamera(const Camera& camera) {
  auto fail = [](const std::string& problem) { throw Error("camera: " + problem); };
  if (camera.width < 1 || camera.width > kMaximumImageSide || camera.height < 1 ||
      camera.height > kMaximumImageSide)
    fail("the image is " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
         "; each side must be in [1, " + std::to_string(kMaximumImageSide) + "]");
  if (!(camera.fovYDegrees > 0.0f && camera.fovYDegrees < 180.0f))
    fail("fov_y_deg " + number(camera.fovYDegrees) + " must be in (0, 180) degrees");
  if (!(camera.nearClip > 0.0f) || !std::isfinite(camera.nearClip))
    fail("near " + number(camera.nearClip) + " must be finite and > 0");
  if (!(camera.farClip > camera.nearClip) || !std::isfinite(camera.farClip))
    fail("far " + number(camera.farClip) + " must be finite and > near (" + number(camera.nearClip) + ")");
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row)
      if (!std::isfinite(camera.worldFromCamera[column][row]))
        fail("world_from_camera has a non-finite element (row " + std::to_string(row) + ", column " +
             std::to_string(column) + ")");
  if (glm::row(camera.worldFromCamera, 3) != glm::vec4(0, 0, 0, 1))
    fail("world_from_camera's last row must be 0 0 0 1 (an affine transform)");
  if (!(std::abs(glm::determinant(glm::mat3(camera.worldFromCamera))) > 1e-12f))
    fail("world_from_camera is singular");
}

void validateParticles(const Particles& particles) {
  const std::size_t count = particles.positions.size();
  auto checkLength = [count](std::size_t length, const char* name) {
    if (length != count)
      throw Error(std::string("particles: ") + name + " has " + std::to_string(length) +
                  " entries, positions " + std::to_string(count));
  };
  checkLength(particles.radii.size(), "radii");
  checkLength(particles.kinds.size(), "kinds");
  checkLength(particles.life.size(), "life");
  checkLength(particles.velocities.size(), "velocities");
  for (std::size_t i = 0; i < count; ++i) {
    const glm::vec3& p = particles.positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error("particles: position " + std::to_string(i) + " is not finite");
    if (!(particles.radii[i] > 0.0f) || !std::isfinite(particles.radii[i]))
      throw Error("particles: radius " + std::to_string(i) + " is " + number(particles.radii[i]) +
                  "; radii must be finite and > 0");
  }
}

void checkImageFitsGl(const GlLimits& limits, int width, int height, const std::string& what) {
  if (width > limits.maxImageWidth() || height > limits.maxImageHeight())
    throw Error(what + " is " + std::to_string(width) + "x" + std::to_string(height) +
                ", larger than this OpenGL allows (" + std::to_string(limits.maxImageWidth()) + "x" +
                std::to_string(limits.maxImageHeight()) + ": GL_MAX_TEXTURE_SIZE " +
                std::to_string(limits.maxTextureSize) + ", GL_MAX_VIEWPORT_DIMS " +
                std::to_string(limits.maxViewportWidth) + "x" + std::to_string(limits.maxViewportHeight) +
                ", GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT " + std::to_string(limits.maxFramebufferWidth) + "x" +
                std::to_string(limits.maxFramebufferHeight) + ")");
}

std::uint64_t availableMemoryBytes() {
  std::uint64_t limit = std::min(memAvailable(), cgroupHeadroom());
  if (const char* megabytes = std::getenv("SPINDRIFT_MEMORY_LIMIT_MB"))
    limit = std::min<std::uint64_t>(limit, std::strtoull(megabytes, nullptr, 10) << 20);
  if (const std::uint64_t explicitBytes = explicitLimit.load()) limit = std::min(limit, explicitBytes);
  return limit;
}

void setMemoryLimitBytes(std::uint64_t bytes) {
  explicitLimit.store(bytes);
}

void requireMemory(std::uint64_t bytes, const std::string& what) {
  const std::uint64_t available = availableMemoryBytes();
  if (bytes <= available) return;
  const char* source =
      explicitLimit.load() && explicitLimit.load() == available ? "the limit set by the caller"
      : std::getenv("SPINDRIFT_MEMORY_LIMIT_MB")                ? "SPINDRIFT_MEMORY_LIMIT_MB or MemAvailable"
                                                                : "MemAvailable and the cgroup's memory.max";
  throw Error(what + " needs " + std::to_string(bytes >> 20) + " MiB, more than the " +
              std::to_string(available >> 20) + " MiB available (" + source + ")");
}

}  // namespace spindrift
