#include <cmath>

#include "io/MeshFile.h"
#include "spindrift/Error.h"
#include "spindrift/Scene.h"

namespace spindrift {
namespace {

TriangleMesh loadMesh(const MeshSource& source, int frame) {
  const std::filesystem::path path = pathForFrame(source.path, frame);
  if (!std::filesystem::exists(path))
    throw Error(path.string() + ": no such mesh file (frame " + std::to_string(frame) + " of " +
                source.path.string() + ")");
  TriangleMesh mesh = readObjMesh(path);
  for (glm::vec3& vertex : mesh.vertices)
    vertex = glm::vec3(source.worldFromFile * glm::vec4(vertex, 1.0f));
  mesh.validate(path.string());  // A huge but finite vertex can still overflow in the transform.
  return mesh;
}

}  // namespace

void TriangleMesh::validate(const std::string& what) const {
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const glm::vec3& v = vertices[i];
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      throw Error(what + ": vertex " + std::to_string(i) + " is not finite");
  }
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int corner = 0; corner < 3; ++corner)
      if (triangles[i][corner] >= vertices.size())
        throw Error(what + ": triangle " + std::to_string(i) + " names vertex " +
                    std::to_string(triangles[i][corner]) + " of " + std::to_string(vertices.size()));
}

void loadMeshes(const Scene& scene, int frame, FrameInputs& inputs) {
  for (const MeshSource& source : scene.occluders)
    inputs.occluders.push_back(loadMesh(source, frame));
  if (scene.liquidMesh && !inputs.liquidMesh) inputs.liquidMesh = loadMesh(*scene.liquidMesh, frame);
}

}  // namespace spindrift
