#pragma once

#include <cstddef>
#include <vector>

#include "framedata/OccluderDepthData.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/FrameInputs.h"

namespace spindrift {

/// A depth prepass of triangles: rasterises meshes (world space) and keeps, per pixel, the minimum of their
/// planar eye depth and a starting depth (the background's). Solid scene geometry drawn this way hides the
/// liquid and foam without a depth pass from the renderer that draws it (Blender's render_pre runs before
/// Cycles); a liquid mesh drawn this way stands in for `background.liquid_depth`.
class OccluderDepthPass {
 public:
  explicit OccluderDepthPass(const ShaderLibrary& shaders);
  /// `startDepth` is an R32F texture of the frame's size, or null for "nothing here" (1e10) everywhere.
  OccluderDepthData run(const std::vector<const TriangleMesh*>& meshes, const Texture2D* startDepth,
                        int width, int height);

 private:
  void upload(const std::vector<const TriangleMesh*>& meshes);

  ProgramObject program_;
  VertexArrayObject vertexArray_;
  BufferObject vertexBuffer_;
  BufferObject indexBuffer_;
  std::size_t vertexBufferBytes_ = 0;
  std::size_t indexBufferBytes_ = 0;
  GLsizei indexCount_ = 0;
  FramebufferObject framebuffer_;
  Texture2D eyeDepth_;
};

}  // namespace spindrift
