#include "io/PngChunkCheck.h"

#include <array>
#include <cstdint>
#include <fstream>
#include <string>

#include "io/ImageFileErrors.h"

namespace spindrift {
namespace {

using image_file_errors::fail;

// The PNG layout (W3C PNG, 5.2-5.3): an 8-byte signature, then chunks of a 4-byte big-endian length, a 4-byte
// type, `length` bytes of data and a 4-byte CRC, the last of type IEND.
constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr std::uint64_t kChunkFraming = 12;             // length, type and CRC
constexpr std::uint32_t kMaxChunkLength = 0x7fffffffu;  // the specification's limit, 2^31 - 1

std::string printableType(const unsigned char* type) {
  std::string name;
  for (int i = 0; i < 4; ++i)
    name += (type[i] >= 0x20 && type[i] < 0x7f) ? char(type[i]) : '?';
  return name;
}

}  // namespace

void checkPngChunkClaims(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::array<unsigned char, 8> signature{};
  if (!file.read(reinterpret_cast<char*>(signature.data()), signature.size()) || signature != kSignature)
    return;
  std::error_code error;
  const std::uint64_t fileSize = std::filesystem::file_size(path, error);
  if (error) return;  // OpenImageIO reports what it cannot read
  std::uint64_t position = signature.size();
  unsigned char header[8];
  while (position + 8 <= fileSize && file.seekg(std::streamoff(position)) &&
         file.read(reinterpret_cast<char*>(header), 8)) {
    const std::uint32_t length = std::uint32_t(header[0]) << 24 | std::uint32_t(header[1]) << 16 |
                                 std::uint32_t(header[2]) << 8 | std::uint32_t(header[3]);
    const std::uint64_t left = fileSize - position;
    if (length > kMaxChunkLength || length + kChunkFraming > left)
      fail(path, "corrupt PNG: chunk '" + printableType(header + 4) + "' claims " + std::to_string(length) +
                     " bytes where " + std::to_string(left < kChunkFraming ? 0 : left - kChunkFraming) +
                     " are left");
    if (std::string(reinterpret_cast<const char*>(header + 4), 4) == "IEND") return;
    position += length + kChunkFraming;
  }
}

}  // namespace spindrift
