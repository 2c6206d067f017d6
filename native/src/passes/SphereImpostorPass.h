#pragma once

#include <vector>

#include <glm/vec4.hpp>

#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "passes/BackgroundPass.h"

namespace spindrift {

/// The nearest liquid surface: exact ray-cast spheres.
struct SurfaceData {
  const Texture2D& eyeDepth;  ///< R32F planar eye depth; 1e10 where no sphere is.
  const Texture2D& normal;    ///< RGBA16F: world normal, and coverage (1 on a sphere, 0 elsewhere).
};

/// Draws every sphere as a camera-facing quad and ray-casts it per pixel (exact depth and normal, with
/// gl_FragDepth), hidden by the background's solids.
class SphereImpostorPass {
 public:
  explicit SphereImpostorPass(const ShaderLibrary& shaders);
  /// `spheres`: world centre in xyz, radius in w; already culled to the view.
  SurfaceData run(const std::vector<glm::vec4>& spheres, const BackgroundData& background, int width, int height);

 private:
  ProgramObject program_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  BufferObject sphereBuffer_;
  std::size_t sphereBufferBytes_ = 0;
  Texture2D eyeDepth_;
  Texture2D normal_;
  Texture2D depthBuffer_;
};

}  // namespace spindrift
