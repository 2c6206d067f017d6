// libFuzzer harness: the scene-file parser (JSON, version 1) and the parameter table behind it. A scene that
// parses must also pass the renderer's own camera check (spindrift/Limits.h): the two must agree.
#include <cstdint>
#include <string>

#include "FuzzInput.h"
#include "spindrift/Error.h"
#include "spindrift/Limits.h"
#include "spindrift/Scene.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Relative paths in the scene resolve here; a file named p.ply exists so that "path" can succeed.
  fuzz::writeInput(reinterpret_cast<const std::uint8_t*>("ply\n"), 4, "p.ply");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const spindrift::Scene scene = spindrift::parseScene(text, fuzz::scratchDirectory() / "scene.json");
    spindrift::validateCamera(scene.camera);  // Throws only if the parser let a bad camera through.
    FUZZ_REQUIRE(scene.camera.width >= 1 && scene.camera.height >= 1);
    for (const spindrift::ParticleSource& source : scene.particles)
      FUZZ_REQUIRE(source.radius > 0.0f);
  } catch (const spindrift::Error& error) {
    const std::string message = error.what();
    // validateCamera's messages start with "camera: "; the parser's name the scene file first.
    FUZZ_REQUIRE(message.rfind("camera: ", 0) != 0);
  }
  return 0;
}
