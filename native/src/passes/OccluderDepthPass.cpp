#include "passes/OccluderDepthPass.h"

#include "passes/FrameUniforms.h"

namespace spindrift {
namespace {

// Grow-only storage: a sequence reallocates only when a frame has more geometry than any before it.
void uploadGrowing(BufferObject& buffer, std::size_t& capacity, const void* data, std::size_t bytes) {
  if (bytes > capacity) {
    buffer = createBuffer();
    glNamedBufferStorage(buffer.id(), GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
    capacity = bytes;
  }
  if (bytes > 0) glNamedBufferSubData(buffer.id(), 0, GLsizeiptr(bytes), data);
}

}  // namespace

OccluderDepthPass::OccluderDepthPass(const ShaderLibrary& shaders)
    : program_(shaders.program({"occluder_depth.vert", "occluder_depth.frag"})),
      vertexArray_(createVertexArray()),
      framebuffer_(createFramebuffer()) {
  glEnableVertexArrayAttrib(vertexArray_.id(), 0);
  glVertexArrayAttribFormat(vertexArray_.id(), 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vertexArray_.id(), 0, 0);
}

void OccluderDepthPass::upload(const std::vector<const TriangleMesh*>& meshes) {
  std::vector<glm::vec3> vertices;
  std::vector<glm::uvec3> triangles;
  for (const TriangleMesh* mesh : meshes) {
    const auto first = std::uint32_t(vertices.size());
    vertices.insert(vertices.end(), mesh->vertices.begin(), mesh->vertices.end());
    for (const glm::uvec3& triangle : mesh->triangles)
      triangles.push_back(triangle + glm::uvec3(first));
  }
  uploadGrowing(vertexBuffer_, vertexBufferBytes_, vertices.data(), vertices.size() * sizeof(glm::vec3));
  uploadGrowing(indexBuffer_, indexBufferBytes_, triangles.data(), triangles.size() * sizeof(glm::uvec3));
  indexCount_ = GLsizei(triangles.size() * 3);
  // The buffers may have been replaced: point the vertex array at the current ones.
  glVertexArrayVertexBuffer(vertexArray_.id(), 0, vertexBuffer_.id(), 0, sizeof(glm::vec3));
  glVertexArrayElementBuffer(vertexArray_.id(), indexBuffer_.id());
  checkGlError("uploading occluder triangles");
}

OccluderDepthData OccluderDepthPass::run(const std::vector<const TriangleMesh*>& meshes,
                                         const Texture2D* startDepth, int width, int height) {
  ensureTexture(eyeDepth_, GL_R32F, width, height);
  bindColorTargets(framebuffer_.id(), {&eyeDepth_});
  if (startDepth) {
    glCopyImageSubData(startDepth->id(), GL_TEXTURE_2D, 0, 0, 0, 0, eyeDepth_.id(), GL_TEXTURE_2D, 0, 0, 0, 0,
                       width, height, 1);
  } else {
    const float noSurface[4] = {1e10f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, noSurface);
  }
  upload(meshes);
  if (indexCount_ > 0) {
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    // The minimum blend keeps the nearest surface without a depth buffer, and folds in the start depth.
    glEnable(GL_BLEND);
    glBlendEquation(GL_MIN);
    glUseProgram(program_.id());
    glBindVertexArray(vertexArray_.id());
    glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_BLEND);
  }
  checkGlError("drawing the occluder depth prepass");
  return {eyeDepth_};
}

}  // namespace spindrift
