#pragma once

#include <cstdint>
#include <string>

#include "spindrift/Camera.h"
#include "spindrift/Particles.h"

namespace spindrift {

/// What the OpenGL implementation allows, queried once per Renderer on its GL thread.
struct GlLimits {
  int maxTextureSize = 0;    ///< GL_MAX_TEXTURE_SIZE: the largest side of a 2D texture.
  int maxViewportWidth = 0;  ///< GL_MAX_VIEWPORT_DIMS.
  int maxViewportHeight = 0;
  int maxFramebufferWidth = 0;  ///< GL_MAX_FRAMEBUFFER_WIDTH / HEIGHT.
  int maxFramebufferHeight = 0;

  /// The largest image the renderer can draw: the smallest of the three limits, per axis.
  int maxImageWidth() const;
  int maxImageHeight() const;
};

/// Rough host memory a frame needs: readback of every layer, the EXR's interleaved copy and, on a software
/// rasteriser (llvmpipe), the textures themselves. Documented in docs/reliability.md.
constexpr std::uint64_t kFrameBytesPerPixel = 1024;
/// Host memory per particle through loading and preparation (particle arrays, neighbour grid, ellipsoids).
constexpr std::uint64_t kPreparationBytesPerParticle = 256;

/// Throws Error naming the limit when a camera cannot be rendered: width or height outside
/// [1, 16384], a vertical field of view outside (0, 180) degrees, near not > 0, far not > near, or a
/// world_from_camera that is not finite, not affine or singular. Scene files are checked the same way when
/// parsed; this covers cameras built through the API.
void validateCamera(const Camera& camera);

/// Throws Error when the arrays of `particles` differ in length, or a particle has a non-finite position or a
/// radius that is not finite and > 0 (loadParticles drops such particles from files; API callers get told).
void validateParticles(const Particles& particles);

/// Throws Error when a width x height image exceeds what `limits` allow, naming the GL limit.
void checkImageFitsGl(const GlLimits& limits, int width, int height, const std::string& what);

/// Bytes this process may still allocate: /proc/meminfo's MemAvailable, lowered by a cgroup memory limit
/// (a Slurm job's, say) and by setMemoryLimitBytes or SPINDRIFT_MEMORY_LIMIT_MB when those are lower.
std::uint64_t availableMemoryBytes();
/// Sets an explicit ceiling (0 removes it). Fuzzers and tests use it; it is process-wide.
void setMemoryLimitBytes(std::uint64_t bytes);
/// Throws Error "<what> needs N MiB, more than the M MiB available (<where the limit comes from>)" when
/// `bytes` exceed availableMemoryBytes(). Called before large allocations, never after.
void requireMemory(std::uint64_t bytes, const std::string& what);

}  // namespace spindrift
