#pragma once

#include "gl/GlObjects.h"

namespace spindrift {

/// Which pixels a full-screen pass has work in, as a depth buffer that holds `emptyDepth` everywhere else: a
/// liquid layer's impostor depth buffer (cleared to 1 for the front layer, 0 for the back one, and written
/// wherever the layer gets a surface) or a mask a pass writes itself. On llvmpipe a shader's early return
/// saves nothing (the rest of it runs masked), but an early depth test that fails for a whole block of pixels
/// skips the shader there: a full-screen pass over the dam break's frame, whose liquid covers 14 % of it,
/// then shades about a fifth of its pixels (docs/frame-cost.md).
struct LayerCoverage {
  const Texture2D* depthBuffer = nullptr;  ///< null: every pixel
  float emptyDepth = 1.0f;
};

/// Attaches the coverage's depth buffer to `framebuffer` and sets the depth state so that the full-screen
/// draws that follow shade only covered pixels: the triangle lies at emptyDepth (glDepthRange) and the test
/// passes where the buffer differs from it. Shaders drawn so must not write gl_FragDepth. With a null depth
/// buffer it detaches any and turns the test off.
void limitToCoverage(GLuint framebuffer, const LayerCoverage& coverage);

/// Detaches the depth buffer and restores the depth state the other passes expect.
void clearCoverageLimit(GLuint framebuffer);

/// Attaches `depthBuffer` to `framebuffer` and sets the depth state so that the next full-screen draw writes
/// its shader's gl_FragDepth into every pixel: a pass that already reads every pixel marks the ones a later
/// pass has work in (0) and the others (1), a LayerCoverage with emptyDepth 1. clearCoverageLimit after it.
void writeCoverage(GLuint framebuffer, const Texture2D& depthBuffer);

}  // namespace spindrift
