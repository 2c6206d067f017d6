#include "passes/EllipsoidImpostorPass.h"

#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include "passes/FrameUniforms.h"

namespace spindrift {

EllipsoidImpostorPass::EllipsoidImpostorPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"ellipsoid_impostor.vert", "ellipsoid_impostor.frag"})),
      clipProgram_(
          shaders.program({"ellipsoid_impostor.vert", "ellipsoid_impostor.frag"}, {"CLIP_TO_DOMAIN"})),
      noSolidsProgram_(
          shaders.program({"ellipsoid_impostor.vert", "ellipsoid_impostor.frag"}, {"NO_SOLIDS"})),
      normalsProgram_(shaders.program({"fullscreen.vert", "ellipsoid_normals.frag"})),
      clipNormalsProgram_(shaders.program({"fullscreen.vert", "ellipsoid_normals.frag"}, {"CLIP_TO_DOMAIN"})),
      depthRangeProgram_(shaders.program({"ellipsoid_impostor.vert", "ellipsoid_impostor.frag"},
                                         {"NO_SOLIDS", "DEPTH_RANGE"})),
      depthRangeEmptyProgram_(shaders.program({"fullscreen.vert", "depth_range_empty.frag"})),
      resolveFramebuffer_(createFramebuffer()),
      emptyVertexArray_(createVertexArray()),
      ellipsoidBuffer_(createBuffer()) {
  front_.framebuffer = createFramebuffer();
  back_.framebuffer = createFramebuffer();
}

SurfaceLayers EllipsoidImpostorPass::run(const std::vector<EllipsoidInstance>& input, const LayerSplit& split,
                                         const BackgroundData* background, const Camera& view,
                                         const DomainBox* domain) {
  ImpostorDraws draws = unclippedDraws(input.size(), split);
  const std::vector<EllipsoidInstance>* list = &input;
  if (domain) {
    ordered_.assign(input.begin(), input.end());
    draws = orderForDomainClip(ordered_, split, *domain);
    list = &ordered_;
  }
  upload(*list);
  resolveRectangle_ = windowRectangleOfSpheres(*list, view);
  drawLayer(front_, false, draws.front, background, view, domain);
  drawLayer(back_, true, draws.back, background, view, domain);
  return {{front_.eyeDepth, front_.normal}, {back_.eyeDepth, back_.normal}};
}

void EllipsoidImpostorPass::upload(const std::vector<EllipsoidInstance>& ellipsoids) {
  // Grow-only storage: a sequence reallocates only when a frame has more particles than any before it.
  const std::size_t bytes = ellipsoids.size() * sizeof(EllipsoidInstance);
  if (bytes > ellipsoidBufferBytes_) {
    ellipsoidBuffer_ = createBuffer();
    glNamedBufferStorage(ellipsoidBuffer_.id(), GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    ellipsoidBufferBytes_ = bytes;
  }
  if (bytes > 0) glNamedBufferSubData(ellipsoidBuffer_.id(), 0, GLsizeiptr(bytes), ellipsoids.data());
  checkGlError("uploading liquid particles");
}

namespace {

// The uniforms of lib/ellipsoid_ray.glsl, which the impostor and the normal resolve programs share. The
// impostor program computes no normal, so the compiler drops domainFromWorld from it, and the programs
// without the clip lack the box: a uniform a program lacks is skipped (location -1), where uniformLocation
// would throw.
void setRayUniforms(GLuint program, bool backFaces, const Camera& view, const DomainBox* domain) {
  const auto location = [program](const char* name) { return glGetUniformLocation(program, name); };
  glProgramUniform1i(program, location("backFaces"), backFaces ? 1 : 0);
  if (!domain) return;
  const glm::mat4 domainFromWorld = glm::inverse(domain->worldFromBox);
  glProgramUniformMatrix4fv(program, location("domainFromWorld"), 1, GL_FALSE, &domainFromWorld[0][0]);
  // The pixels' rays in the box's frame (PixelRays), which every fragment would otherwise compute: the rays
  // of lib/frame.glsl's cameraRayFromFragCoord, from the view's frame uniforms.
  const glm::mat4 domainFromCamera = domainFromWorld * view.worldFromCamera;
  const glm::mat3 linear(domainFromCamera);
  const FrameUniforms frame = FrameUniforms::fromCamera(view);
  const glm::vec2 tanHalfFov(frame.tanHalfFov),
      perPixel = 2.0f * tanHalfFov * glm::vec2(frame.viewportSize.z, frame.viewportSize.w);
  const glm::vec3 atOrigin = linear * glm::vec3(-tanHalfFov, -1.0f);
  const glm::vec3 perPixelX = linear * glm::vec3(perPixel.x, 0.0f, 0.0f);
  const glm::vec3 perPixelY = linear * glm::vec3(0.0f, perPixel.y, 0.0f);
  const glm::vec3 camera(domainFromCamera[3]);
  glProgramUniform3fv(program, location("domainRayAtOrigin"), 1, &atOrigin[0]);
  glProgramUniform3fv(program, location("domainRayPerPixelX"), 1, &perPixelX[0]);
  glProgramUniform3fv(program, location("domainRayPerPixelY"), 1, &perPixelY[0]);
  glProgramUniform3fv(program, location("domainCamera"), 1, &camera[0]);
  glProgramUniform3fv(program, location("domainLow"), 1, &domain->low[0]);
  glProgramUniform3fv(program, location("domainHigh"), 1, &domain->high[0]);
}

}  // namespace

SurfaceLayers EllipsoidImpostorPass::runDepthRange(const std::vector<EllipsoidInstance>& ellipsoids,
                                                   const Camera& view) {
  const int width = view.width, height = view.height;
  upload(ellipsoids);
  ensureTexture(front_.eyeDepth, GL_R32F, width, height);
  ensureTexture(back_.eyeDepth, GL_R32F, width, height);
  ensureTexture(farthestExit_, GL_R32F, width, height);
  for (Target* target : {&front_, &back_}) {
    ensureTexture(target->normal, GL_RGBA16F, width, height);
    const float noNormal[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(target->normal.id(), 0, GL_RGBA, GL_FLOAT, noNormal);
  }
  const float noSurface = 1e10f, noExit = 0.0f;
  glClearTexImage(front_.eyeDepth.id(), 0, GL_RED, GL_FLOAT, &noSurface);
  glClearTexImage(farthestExit_.id(), 0, GL_RED, GL_FLOAT, &noExit);

  if (!ellipsoids.empty()) {
    bindColorTargets(resolveFramebuffer_.id(), {&front_.eyeDepth, &farthestExit_});
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);  // GL_MIN and GL_MAX ignore the blend factors
    glBlendEquationi(0, GL_MIN);
    glBlendEquationi(1, GL_MAX);
    const GLuint program = depthRangeProgram_.id();
    glUseProgram(program);
    setRayUniforms(program, true, view, nullptr);
    glUniform1i(uniformLocation(program, "firstEllipsoid"), 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, ellipsoidBuffer_.id());
    glBindVertexArray(emptyVertexArray_.id());
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(3 * ellipsoids.size()));
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_BLEND);
    checkGlError("drawing the liquid particles' depth range");
  }

  glUseProgram(depthRangeEmptyProgram_.id());
  bindColorTargets(resolveFramebuffer_.id(), {&back_.eyeDepth});
  glBindTextureUnit(0, front_.eyeDepth.id());
  glBindTextureUnit(1, farthestExit_.id());
  drawFullscreenTriangle(emptyVertexArray_.id());
  checkGlError("marking the depth range's empty pixels");
  return {{front_.eyeDepth, front_.normal}, {back_.eyeDepth, back_.normal}};
}

void EllipsoidImpostorPass::drawLayer(Target& target, bool backFaces, const std::vector<ImpostorDraw>& draws,
                                      const BackgroundData* background, const Camera& view,
                                      const DomainBox* domain) {
  const int width = view.width, height = view.height;
  ensureTexture(target.eyeDepth, GL_R32F, width, height);
  ensureTexture(target.winner, GL_R32UI, width, height);
  ensureTexture(target.normal, GL_RGBA16F, width, height);
  ensureTexture(target.depthBuffer, GL_DEPTH_COMPONENT32F, width, height);
  const GLuint framebuffer = target.framebuffer.id();
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, target.eyeDepth.id(), 0);
  glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT1, target.winner.id(), 0);
  glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, target.depthBuffer.id(), 0);
  const GLenum attachments[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer, 2, attachments);

  const float noSurface[4] = {1e10f, 0.0f, 0.0f, 0.0f};
  const GLuint noWinner[4] = {0, 0, 0, 0};
  // The front layer keeps the nearest surface, the back layer the farthest: opposite tests, opposite clears.
  const float clearDepth = backFaces ? 0.0f : 1.0f;
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, noSurface);
  glClearNamedFramebufferuiv(framebuffer, GL_COLOR, 1, noWinner);
  glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &clearDepth);
  const float noNormal[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  if (draws.empty()) {
    glClearTexImage(target.normal.id(), 0, GL_RGBA, GL_FLOAT, noNormal);
    return;
  }

  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(backFaces ? GL_GREATER : GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, ellipsoidBuffer_.id());
  if (background) glBindTextureUnit(0, background->eyeDepth.id());
  glBindVertexArray(emptyVertexArray_.id());
  bool anyClipped = false;
  for (const ImpostorDraw& draw : draws) {
    const GLuint program = draw.clip ? clipProgram_.id() : background ? program_.id() : noSolidsProgram_.id();
    anyClipped = anyClipped || draw.clip;
    glUseProgram(program);
    setRayUniforms(program, backFaces, view, domain);
    glUniform1i(uniformLocation(program, "firstEllipsoid"), draw.first);
    glDrawArrays(GL_TRIANGLES, 0, 3 * draw.count);
  }
  glDisable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  checkGlError(backFaces ? "drawing back faces of liquid particles"
                         : "drawing front faces of liquid particles");

  // The normals of the winning ellipsoids only, within the rectangle that holds them all: on llvmpipe the
  // resolve's pixels without a winner cost as much as the others (an `if` runs for every pixel), and the
  // dam break's liquid covers a fifth of its frame (docs/frame-cost.md, session 40).
  const GLuint normalsProgram = anyClipped ? clipNormalsProgram_.id() : normalsProgram_.id();
  glUseProgram(normalsProgram);
  setRayUniforms(normalsProgram, backFaces, view, domain);
  clearColorTargets(resolveFramebuffer_.id(), {&target.normal}, noNormal);
  glBindTextureUnit(0, target.winner.id());
  glEnable(GL_SCISSOR_TEST);
  glScissor(resolveRectangle_.x, resolveRectangle_.y, resolveRectangle_.width, resolveRectangle_.height);
  drawFullscreenTriangle(emptyVertexArray_.id());
  glDisable(GL_SCISSOR_TEST);
  checkGlError("resolving the liquid particles' normals");
}

}  // namespace spindrift
