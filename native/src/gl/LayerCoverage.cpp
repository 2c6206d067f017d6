#include "gl/LayerCoverage.h"

namespace spindrift {

void limitToCoverage(GLuint framebuffer, const LayerCoverage& coverage) {
  if (!coverage.depthBuffer) {
    clearCoverageLimit(framebuffer);
    return;
  }
  glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, coverage.depthBuffer->id(), 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_NOTEQUAL);
  glDepthMask(GL_FALSE);
  glDepthRangef(coverage.emptyDepth, coverage.emptyDepth);
}

void writeCoverage(GLuint framebuffer, const Texture2D& depthBuffer) {
  glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depthBuffer.id(), 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  glDepthMask(GL_TRUE);
  glDepthRangef(0.0f, 1.0f);
}

void clearCoverageLimit(GLuint framebuffer) {
  glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, 0, 0);
  glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDepthRangef(0.0f, 1.0f);
}

}  // namespace spindrift
