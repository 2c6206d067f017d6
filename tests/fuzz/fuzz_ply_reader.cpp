// libFuzzer harness: the PLY reader (ASCII and binary, both byte orders, any property order and type).
#include <cstdint>

#include "FuzzInput.h"
#include "io/ParticleFile.h"
#include "spindrift/Error.h"
#include "spindrift/Limits.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  spindrift::setMemoryLimitBytes(std::uint64_t(512) << 20);  // Beyond this a header is lying; say so.
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = fuzz::writeInput(data, size, "input.ply");
  try {
    fuzz::checkParticleArrays(spindrift::readPly(path));
  } catch (const spindrift::Error&) {
  }
  return 0;
}
