#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "gl/GlObjects.h"

namespace spindrift {

/// What the program cache did in this process.
struct ProgramCacheCounts {
  int loaded = 0;    ///< Programs made from a cached binary.
  int compiled = 0;  ///< Programs compiled from source (and stored, where the cache is on).
  int rejected = 0;  ///< Cache files that were unreadable, corrupt or refused by the driver, then rebuilt.
};

/// Linked program binaries on disk, shared by every process on the machine, so only the first process after a
/// shader or driver change pays for compiling (glGetProgramBinary / glProgramBinary). A file is named by a
/// hash of the driver's identity and every stage's expanded source, so a changed shader or driver finds no
/// file and recompiles; a file carries its length and checksum, so a truncated or corrupt one is ignored and
/// replaced. Files are written to a temporary name and renamed, so concurrent processes never read half a
/// file. Must be used on the GL thread.
class ProgramCache {
 public:
  /// A cache in `directory` for the driver `driverIdentity`; an empty directory turns the cache off.
  ProgramCache(std::filesystem::path directory, std::string driverIdentity);
  /// The cache for the current context: $SPINDRIFT_PROGRAM_CACHE (empty or "off" turns it off), else
  /// $XDG_CACHE_HOME/spindrift/programs, else ~/.cache/spindrift/programs; off when the driver offers no
  /// program binary format. The driver identity is GL_VENDOR, GL_RENDERER and GL_VERSION.
  static ProgramCache forCurrentContext();

  bool enabled() const { return !directory_.empty(); }
  const std::filesystem::path& directory() const { return directory_; }
  /// The file that holds the program of these expanded stage sources.
  std::filesystem::path fileFor(const std::vector<std::string>& stageSources) const;
  /// The cached program for these sources, linked; an empty object when there is none (or it was rejected).
  ProgramObject load(const std::vector<std::string>& stageSources);
  /// Stores a linked program made with GL_PROGRAM_BINARY_RETRIEVABLE_HINT; a failure to write is ignored (the
  /// next process compiles again).
  void store(const std::vector<std::string>& stageSources, GLuint program);

  ProgramCacheCounts counts;

 private:
  std::filesystem::path directory_;
  std::string driverIdentity_;
};

}  // namespace spindrift
