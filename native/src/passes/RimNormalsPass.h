#pragma once

#include "framedata/DepthLayers.h"
#include "framedata/PixelTiles.h"
#include "framedata/SmoothedDepth.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// Turns a body's front normals within 8 pixels of its silhouette towards the circle its front and back
/// layers give there (liquid.rim_normals; shaders/rim_normals.frag says how and docs/liquid.md, "Rim
/// normals", what it buys). Two draws: each pixel's nearest uncovered pixel along its row
/// (rim_edge_rows.frag), then the nearest in the plane from those rows and the bent normal. The frame's
/// uniform block (binding 0) must be current. The result lives in the pass's own texture until its next run.
class RimNormalsPass {
 public:
  explicit RimNormalsPass(const ShaderLibrary& shaders);
  /// `solidEyeDepth` is the background's solids and `domain` a Mantaflow domain's box (null: none): a
  /// liquid's edge against either is not a silhouette. `particleRadius` is the liquid's world radius. With
  /// `tiles` (which must mark every tile where the front layer has a surface) only those tiles get normals;
  /// the rest hold none.
  RecomputedNormals run(const SurfaceLayers& body, const Texture2D& solidEyeDepth, const DomainBox* domain,
                        float particleRadius, const PixelTiles* tiles, int width, int height);

 private:
  ProgramObject edgeRowsProgram_;
  ProgramObject normalsProgram_;
  VertexArrayObject emptyVertexArray_;
  FramebufferObject framebuffer_;
  Texture2D edgeRows_;  ///< R16F: rim_edge_rows.frag's offsets (whole numbers up to 8, or 1e4)
  Texture2D normal_;
};

}  // namespace spindrift
