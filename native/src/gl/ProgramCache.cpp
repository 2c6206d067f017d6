#include "gl/ProgramCache.h"

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

namespace spindrift {
namespace {

constexpr char kMagic[8] = {'S', 'P', 'D', 'P', 'R', 'O', 'G', '1'};

// The file's fixed header; the binary follows.
struct FileHeader {
  char magic[8];
  std::uint32_t format;
  std::uint32_t reserved;
  std::uint64_t length;
  std::uint64_t checksum;
};

// FNV-1a, 64 bits: names files and checks their contents (not a defence against tampering, which a cache in
// the user's own directory does not need).
std::uint64_t fnv1a(const void* data, std::size_t size, std::uint64_t hash = 0xcbf29ce484222325ull) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i)
    hash = (hash ^ bytes[i]) * 0x100000001b3ull;
  return hash;
}

std::string glString(GLenum name) {
  const GLubyte* text = glGetString(name);
  return text ? reinterpret_cast<const char*>(text) : "";
}

std::filesystem::path defaultDirectory() {
  if (const char* chosen = std::getenv("SPINDRIFT_PROGRAM_CACHE")) {
    if (!*chosen || std::strcmp(chosen, "off") == 0) return {};
    return chosen;
  }
  if (const char* cacheHome = std::getenv("XDG_CACHE_HOME"); cacheHome && *cacheHome)
    return std::filesystem::path(cacheHome) / "spindrift/programs";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache/spindrift/programs";
  return {};
}

}  // namespace

ProgramCache::ProgramCache(std::filesystem::path directory, std::string driverIdentity)
    : directory_(std::move(directory)), driverIdentity_(std::move(driverIdentity)) {}

ProgramCache ProgramCache::forCurrentContext() {
  GLint formats = 0;
  glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
  const std::string identity =
      glString(GL_VENDOR) + "\n" + glString(GL_RENDERER) + "\n" + glString(GL_VERSION);
  return ProgramCache(formats > 0 ? defaultDirectory() : std::filesystem::path(), identity);
}

std::filesystem::path ProgramCache::fileFor(const std::vector<std::string>& stageSources) const {
  std::uint64_t hash = fnv1a(driverIdentity_.data(), driverIdentity_.size());
  for (const std::string& source : stageSources) {
    const std::uint64_t length = source.size();  // Lengths keep ("ab", "c") and ("a", "bc") apart.
    hash = fnv1a(&length, sizeof length, hash);
    hash = fnv1a(source.data(), source.size(), hash);
  }
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.bin", static_cast<unsigned long long>(hash));
  return directory_ / name;
}

ProgramObject ProgramCache::load(const std::vector<std::string>& stageSources) {
  if (!enabled()) return {};
  const std::filesystem::path path = fileFor(stageSources);
  std::ifstream file(path, std::ios::binary);
  if (!file) return {};
  const std::vector<char> contents((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  FileHeader header{};
  const bool whole = contents.size() >= sizeof header &&
                     (std::memcpy(&header, contents.data(), sizeof header), true) &&
                     std::memcmp(header.magic, kMagic, sizeof kMagic) == 0 &&
                     header.length == contents.size() - sizeof header &&
                     header.checksum == fnv1a(contents.data() + sizeof header, header.length);
  if (whole) {
    ProgramObject program(glCreateProgram());
    glProgramBinary(program.id(), header.format, contents.data() + sizeof header, GLsizei(header.length));
    GLint linked = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &linked);
    while (glGetError() != GL_NO_ERROR) {
      linked = GL_FALSE;  // GL_INVALID_ENUM for a format this driver no longer knows.
    }
    if (linked) {
      ++counts.loaded;
      return program;
    }
  }
  ++counts.rejected;
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  return {};
}

void ProgramCache::store(const std::vector<std::string>& stageSources, GLuint program) {
  if (!enabled()) return;
  GLint length = 0;
  glGetProgramiv(program, GL_PROGRAM_BINARY_LENGTH, &length);
  if (length <= 0) return;
  std::vector<char> binary(std::size_t(length), '\0');
  GLsizei written = 0;
  GLenum format = 0;
  glGetProgramBinary(program, length, &written, &format, binary.data());
  if (glGetError() != GL_NO_ERROR || written <= 0) return;
  FileHeader header{};
  std::memcpy(header.magic, kMagic, sizeof kMagic);
  header.format = format;
  header.length = std::uint64_t(written);
  header.checksum = fnv1a(binary.data(), std::size_t(written));
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  const std::filesystem::path path = fileFor(stageSources);
  static std::atomic<unsigned> stores{0};  // Several renderers of one process may store at once.
  const std::filesystem::path temporary =
      path.string() + "." + std::to_string(getpid()) + "." + std::to_string(stores++) + ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary);
    file.write(reinterpret_cast<const char*>(&header), sizeof header);
    file.write(binary.data(), written);
    if (!file) {
      std::filesystem::remove(temporary, error);
      return;
    }
  }
  std::filesystem::rename(temporary, path, error);
  if (error) std::filesystem::remove(temporary, error);
}

}  // namespace spindrift
