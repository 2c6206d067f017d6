#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "spindrift/FrameInputs.h"
#include "spindrift/Limits.h"
#include "spindrift/RenderResult.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// Renders frames of scenes. It owns a thread of its own on which an EGL OpenGL 4.5 context is current, so a
/// host application's GL context (Blender's, for one) is never touched. Construction throws Error with one
/// clear line when no OpenGL 4.5 context can be made. A Renderer renders one frame at a time; GL objects
/// live as long as the Renderer and are reused across frames.
class Renderer {
 public:
  /// Shaders from findShaderDirectory(): $SPINDRIFT_SHADER_DIR, or `share/spindrift/shaders` beside the
  /// library's directory.
  Renderer();
  /// Shaders from an explicit directory (the Blender add-on keeps them beside its module).
  /// Both make the GL context (an Error if there is none) and return while the GL thread builds the shader
  /// programs; an Error in building them comes out of every frame.
  explicit Renderer(const std::filesystem::path& shaderDirectory);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Loads the frame's particles and background, renders every pass the scene needs and reads them back.
  RenderResult renderFrame(const Scene& scene, int frame);
  /// The same, with what a host hands over in memory: particles added to the files', occluder and liquid
  /// meshes beside the scene's mesh files, and a background colour and depth instead of its files.
  RenderResult renderFrame(const Scene& scene, int frame, const FrameInputs& inputs);
  /// Renders already loaded particles (world space); `counts` describes them for the stats.
  RenderResult renderParticles(const Scene& scene, const Particles& particles, int frame);

  /// Also return the intermediate textures (the four depth layers before and after smoothing) as layers
  /// named like "aggregate_front_depth_smoothed", for documentation and debugging. Off by default.
  void setIntermediateLayers(bool enabled);
  /// Reads back only these layers (names as in the EXR: composite, liquid, depth, foam, ...); empty, the
  /// default, reads all. Passes whose results reach no chosen layer are not run (`FrameStats::skipped` says
  /// so). Throws Error naming the valid layers when a name is unknown.
  void setLayers(const std::vector<std::string>& names);

  /// GL_RENDERER and GL_VERSION of the renderer's context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string glRenderer() const;
  std::string glVersion() const;
  /// The texture and framebuffer limits of the renderer's context.
  const GlLimits& glLimits() const;

  /// Throws Error naming the limit when the scene's camera is invalid or its image, with `particleCount`
  /// particles, exceeds the GL limits or the memory available (spindrift/Limits.h). renderFrame and
  /// renderParticles call it before allocating anything for the frame.
  void checkFrame(const Scene& scene, std::size_t particleCount) const;

 private:
  struct Impl;
  struct FrameExtras;
  RenderResult renderPrepared(const Scene& scene, const Particles& particles, int frame,
                              const FrameExtras& extras);
  std::unique_ptr<Impl> impl_;
};

}  // namespace spindrift
