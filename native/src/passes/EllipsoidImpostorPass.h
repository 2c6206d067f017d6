#pragma once

#include <vector>

#include "framedata/BackgroundData.h"
#include "framedata/DepthLayers.h"
#include "gl/GlObjects.h"
#include "gl/ShaderLibrary.h"
#include "prep/DomainClipOrder.h"
#include "prep/LiquidPreparation.h"
#include "prep/WindowRectangle.h"
#include "spindrift/Scene.h"

namespace spindrift {

/// Ray-casts ellipsoid impostors (Sigg et al. 2006) into a front and a back depth layer with exact per-pixel
/// depth and analytic normals: the liquid paper's section 4.2. Spheres are ellipsoids with equal axes. The
/// draw keeps each pixel's winning ellipsoid, and a full-screen resolve computes the normals of the winners
/// only (on llvmpipe every fragment of the draw pays for its whole shader; docs/frame-cost.md).
class EllipsoidImpostorPass {
 public:
  explicit EllipsoidImpostorPass(const ShaderLibrary& shaders);
  /// `split` says which ellipsoids each layer draws (all of them by default); `background`, when not null,
  /// hides the ellipsoids whose front lies behind its solids (a light's view has none); `view` is the camera
  /// whose frame block is bound (binding 0); `domain`, when not null, clips the surfaces to a Mantaflow
  /// domain's box. A view that needs depth alone draws with runDepthRange.
  SurfaceLayers run(const std::vector<EllipsoidInstance>& ellipsoids, const LayerSplit& split,
                    const BackgroundData* background, const Camera& view, const DomainBox* domain = nullptr);
  /// The two layers' depths alone, for a view without solids or a domain (the sky's): one draw of every
  /// ellipsoid keeps each pixel's nearest entry and farthest exit by blending, where `run` draws twice with
  /// opposite depth tests. On llvmpipe each draw pays for its vertices and triangles on one thread (the dam
  /// break's sky view: about 35 ms a draw; docs/frame-cost.md). Drawing an ellipsoid into a layer it is
  /// hidden from changes nothing there, so a LayerSplit is not needed. The normals are left zero.
  SurfaceLayers runDepthRange(const std::vector<EllipsoidInstance>& ellipsoids, const Camera& view);

 private:
  struct Target {
    FramebufferObject framebuffer;
    Texture2D eyeDepth;
    Texture2D winner;  ///< R32UI: the index + 1 of the ellipsoid that holds the pixel's surface, 0 if none.
    Texture2D normal;  ///< Resolved from the winners after the draw.
    Texture2D depthBuffer;
  };
  void upload(const std::vector<EllipsoidInstance>& ellipsoids);
  void drawLayer(Target& target, bool backFaces, const std::vector<ImpostorDraw>& draws,
                 const BackgroundData* background, const Camera& view, const DomainBox* domain);

  // The impostor program with and without the clip to a domain's box (lib/ellipsoid_ray.glsl; only the
  // ellipsoids that reach the box's faces are drawn with it, orderForDomainClip) and without the solids test
  // (the lights' views); the normal resolve with and without the clip.
  ProgramObject program_;
  ProgramObject clipProgram_;
  ProgramObject noSolidsProgram_;
  ProgramObject normalsProgram_;  // the normal resolve: the winners' ray casts repeated, one per pixel
  ProgramObject clipNormalsProgram_;
  ProgramObject depthRangeProgram_;         // runDepthRange's draw (DEPTH_RANGE, NO_SOLIDS)
  ProgramObject depthRangeEmptyProgram_;    // marks its back layer empty where nothing was drawn
  Texture2D farthestExit_;                  // runDepthRange's GL_MAX target, cleared to 0
  std::vector<EllipsoidInstance> ordered_;  // the list in draw order, when a domain reorders it
  FramebufferObject resolveFramebuffer_;
  WindowRectangle resolveRectangle_;  // the normal resolve's scissor: where the drawn ellipsoids can lie
  VertexArrayObject emptyVertexArray_;
  BufferObject ellipsoidBuffer_;
  std::size_t ellipsoidBufferBytes_ = 0;
  Target front_;
  Target back_;
};

}  // namespace spindrift
