#include "io/ParticleFile.h"

#include "spindrift/Error.h"

namespace spindrift {

ParticleFileData readParticleFile(const std::filesystem::path& path, const std::string& gridName) {
  const std::string extension = path.extension().string();
  if (extension == ".vdb") return readVdbPoints(path, gridName);
  if (extension == ".ply") return readPly(path);
  throw Error(path.string() + ": unknown particle file type (expected .vdb or .ply)");
}

}  // namespace spindrift
