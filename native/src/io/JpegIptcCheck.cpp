#include "io/JpegIptcCheck.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "io/OiioErrors.h"

namespace spindrift {
namespace {

using oiio_errors::fail;

// JPEG's markers (ITU T.81, B.1): 0xFF, a code, and for most a 2-byte big-endian length that counts itself.
constexpr unsigned char kStartOfScan = 0xDA;
constexpr unsigned char kEndOfImage = 0xD9;
constexpr unsigned char kApp13 = 0xED;
// What OpenImageIO 2.4's JpgInput::jpeg_decode_iptc reads from an APP13 segment: "Photoshop 3.0\0", "8BIM", a
// 2-byte resource type (1028 for IPTC), 4 bytes it skips, a 2-byte size and then that many bytes of IPTC.
constexpr char kPhotoshop[] = "Photoshop 3.0";  // with its terminator: 14 bytes
constexpr std::size_t kPhotoshopBytes = sizeof kPhotoshop;
constexpr std::size_t kIptcSizeEnd = kPhotoshopBytes + 4 + 2 + 4 + 2;  // 26
constexpr unsigned kIptcResource = 1028;
constexpr std::size_t kMaxScannedBytes = std::size_t(4) << 20;  // markers before the image data are small

unsigned be16(const unsigned char* bytes) {
  return unsigned(bytes[0]) << 8 | bytes[1];
}

// Whether OpenImageIO would read past `length` bytes of an APP13 segment's data.
bool iptcOverruns(const unsigned char* data, std::size_t length) {
  // strcmp against "Photoshop 3.0" reads on while the bytes match.
  const std::size_t compared = std::min(length, kPhotoshopBytes);
  if (std::memcmp(data, kPhotoshop, compared) != 0) return false;
  if (length < kPhotoshopBytes + 4) return true;
  if (std::memcmp(data + kPhotoshopBytes, "8BIM", 4) != 0) return false;
  if (length < kIptcSizeEnd) return true;
  if (be16(data + kPhotoshopBytes + 4) != kIptcResource) return false;
  return kIptcSizeEnd + be16(data + kIptcSizeEnd - 2) > length;
}

}  // namespace

void checkJpegIptcClaims(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::vector<unsigned char> bytes(2);
  if (!file.read(reinterpret_cast<char*>(bytes.data()), 2) || bytes[0] != 0xFF || bytes[1] != 0xD8) return;
  bytes.resize(kMaxScannedBytes);
  file.read(reinterpret_cast<char*>(bytes.data() + 2), std::streamsize(bytes.size() - 2));
  bytes.resize(2 + std::size_t(file.gcount()));
  // As libjpeg's next_marker: bytes that are not 0xFF are skipped (it warns of "extraneous bytes"), then fill
  // bytes 0xFF, and 0xFF 0x00 is data, not a marker.
  std::size_t position = 2;
  while (position + 1 < bytes.size()) {
    if (bytes[position] != 0xFF || bytes[position + 1] == 0xFF) {
      ++position;
      continue;
    }
    const unsigned char code = bytes[position + 1];
    if (code == 0x00) {
      position += 2;
      continue;
    }
    if (code == kStartOfScan || code == kEndOfImage) return;
    if (code == 0x01 || (code >= 0xD0 && code <= 0xD7)) {  // no length
      position += 2;
      continue;
    }
    if (position + 4 > bytes.size()) return;
    const std::size_t length = be16(&bytes[position + 2]);
    if (length < 2) return;  // libjpeg refuses it
    const std::size_t dataStart = position + 4;
    const std::size_t dataLength = std::min(length - 2, bytes.size() - dataStart);
    if (code == kApp13 && iptcOverruns(&bytes[dataStart], dataLength))
      fail(path, "corrupt JPEG: its Photoshop IPTC block claims more than its " + std::to_string(dataLength) +
                     "-byte APP13 segment holds");
    position += 2 + length;
  }
}

}  // namespace spindrift
