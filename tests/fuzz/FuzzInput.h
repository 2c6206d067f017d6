#pragma once
// Shared by the libFuzzer harnesses: the readers take paths, so each input is written to a file in a
// directory of the process's own (in /dev/shm when it exists, so the fuzzer does not wear a disk).

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace fuzz {

inline const std::filesystem::path& scratchDirectory() {
  static const std::filesystem::path directory = [] {
    const std::filesystem::path base = std::filesystem::exists("/dev/shm") ? "/dev/shm" : "/tmp";
    const std::filesystem::path path = base / ("spindrift-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(scratchDirectory(), ignored);
    });
    return path;
  }();
  return directory;
}

inline std::filesystem::path writeInput(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const std::filesystem::path path = scratchDirectory() / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

// A broken invariant is a finding: abort so libFuzzer saves the input.
#define FUZZ_REQUIRE(condition)                                                               \
  do {                                                                                        \
    if (!(condition)) {                                                                       \
      std::fprintf(stderr, "invariant broken: %s (%s:%d)\n", #condition, __FILE__, __LINE__); \
      std::abort();                                                                           \
    }                                                                                         \
  } while (0)

// What every particle reader promises: each optional array is empty or has one entry per position.
template <typename ParticleFileData>
void checkParticleArrays(const ParticleFileData& particles) {
  const std::size_t count = particles.positions.size();
  FUZZ_REQUIRE(particles.radii.empty() || particles.radii.size() == count);
  FUZZ_REQUIRE(particles.typeFlags.empty() || particles.typeFlags.size() == count);
  FUZZ_REQUIRE(particles.life.empty() || particles.life.size() == count);
  FUZZ_REQUIRE(particles.velocities.empty() || particles.velocities.size() == count);
}

}  // namespace fuzz
