#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/MeshFile.h"
#include "spindrift/Error.h"

namespace spindrift {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, int line, const std::string& what) {
  throw Error(path.string() + ": line " + std::to_string(line) + ": " + what);
}

// The vertex index of one `f` corner ("7", "7/1", "7//3", "-2/1/1"), zero-based.
std::uint32_t cornerIndex(const std::string& word, std::size_t vertexCount, const std::filesystem::path& path,
                          int line) {
  const std::string number = word.substr(0, word.find('/'));
  char* end = nullptr;
  errno = 0;
  const long long index = std::strtoll(number.c_str(), &end, 10);
  if (number.empty() || *end != '\0' || errno != 0) fail(path, line, "'" + word + "' is not a vertex index");
  // OBJ counts from 1; negative indices count back from the last vertex read.
  const long long zeroBased = index > 0 ? index - 1 : (long long)vertexCount + index;
  if (index == 0 || zeroBased < 0 || zeroBased >= (long long)vertexCount)
    fail(path, line,
         "vertex index " + number + " is outside the " + std::to_string(vertexCount) +
             " vertices read so far");
  return std::uint32_t(zeroBased);
}

}  // namespace

TriangleMesh readObjMesh(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file) throw Error(path.string() + ": cannot open the mesh file");
  TriangleMesh mesh;
  std::string text;
  int line = 0;
  std::vector<std::uint32_t> corners;
  while (std::getline(file, text)) {
    ++line;
    std::istringstream words(text);
    std::string statement;
    if (!(words >> statement) || statement[0] == '#') continue;
    if (statement == "v") {
      // strtof, not >>: it reads "nan" and "inf", which are then reported as what they are.
      float xyz[3];
      for (float& value : xyz) {
        std::string word;
        char* end = nullptr;
        if (!(words >> word) || (value = std::strtof(word.c_str(), &end), *end != '\0'))
          fail(path, line, "expected 'v x y z'");
      }
      if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
        fail(path, line, "the vertex is not finite");
      mesh.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
    } else if (statement == "f") {
      corners.clear();
      for (std::string word; words >> word;)
        corners.push_back(cornerIndex(word, mesh.vertices.size(), path, line));
      if (corners.size() < 3) fail(path, line, "a face needs at least three vertices");
      for (std::size_t i = 1; i + 1 < corners.size(); ++i)
        mesh.triangles.emplace_back(corners[0], corners[i], corners[i + 1]);
    }
  }
  if (file.bad()) throw Error(path.string() + ": cannot read the mesh file");
  return mesh;
}

}  // namespace spindrift
