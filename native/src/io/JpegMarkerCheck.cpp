#include "io/JpegMarkerCheck.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "io/ImageFileErrors.h"

namespace spindrift {
namespace {

using image_file_errors::fail;

// JPEG's markers (ITU T.81, B.1): 0xFF, a code, and for most a 2-byte big-endian length that counts itself.
constexpr unsigned char kStartOfScan = 0xDA;
constexpr unsigned char kEndOfImage = 0xD9;
constexpr unsigned char kApp1 = 0xE1;
constexpr unsigned char kApp2 = 0xE2;
constexpr unsigned char kApp13 = 0xED;
// What OpenImageIO 2.4's JpgInput reads from the segments libjpeg saves. It compares each with strcmp, which
// reads on while the bytes match: "Exif" and "http://ns.adobe.com/xap/1.0/" (APP1), "ICC_PROFILE" (APP2),
// "Photoshop 3.0" (APP13). Then: Exif's data from byte 6 on, data_length - 6 of it; an ICC segment's bytes 12
// and 13 and data_length - 14 from byte 14; and from "Photoshop 3.0\0", "8BIM", a 2-byte resource type (1028
// for IPTC), 4 bytes it skips, a 2-byte size and that many bytes of IPTC.
constexpr char kPhotoshop[] = "Photoshop 3.0";  // with its terminator: 14 bytes
constexpr std::size_t kPhotoshopBytes = sizeof kPhotoshop;
constexpr std::size_t kIptcSizeEnd = kPhotoshopBytes + 4 + 2 + 4 + 2;  // 26
constexpr unsigned kIptcResource = 1028;
constexpr std::size_t kExifHeaderBytes = 6;
constexpr std::size_t kIccHeaderBytes = 14;
constexpr std::size_t kMaxScannedBytes = std::size_t(4) << 20;  // markers before the image data are small

unsigned be16(const unsigned char* bytes) {
  return unsigned(bytes[0]) << 8 | bytes[1];
}

// Whether strcmp(data, name) would read past `length` bytes: the data ends before a byte that differs from
// `name` (its terminator included).
bool endsInside(const unsigned char* data, std::size_t length, const char* name) {
  const std::size_t nameBytes = std::strlen(name) + 1;
  return length < nameBytes && std::memcmp(data, name, length) == 0;
}

// Whether the data starts with `name` and its terminator.
bool startsWith(const unsigned char* data, std::size_t length, const char* name) {
  const std::size_t nameBytes = std::strlen(name) + 1;
  return length >= nameBytes && std::memcmp(data, name, nameBytes) == 0;
}

// What OpenImageIO would read past in one saved segment, or nullptr.
const char* overrun(unsigned char code, const unsigned char* data, std::size_t length) {
  if (code == kApp1) {
    if (endsInside(data, length, "Exif") || endsInside(data, length, "http://ns.adobe.com/xap/1.0/"))
      return "its APP1 segment ends inside the name it is compared with";
    if (startsWith(data, length, "Exif") && length < kExifHeaderBytes) return "its Exif segment is cut short";
  } else if (code == kApp2) {
    if (endsInside(data, length, "ICC_PROFILE"))
      return "its APP2 segment ends inside the name it is compared with";
    if (startsWith(data, length, "ICC_PROFILE") && length < kIccHeaderBytes)
      return "its ICC profile segment is cut short";
  } else if (code == kApp13) {
    if (endsInside(data, length, kPhotoshop))
      return "its APP13 segment ends inside the name it is compared with";
    if (!startsWith(data, length, kPhotoshop)) return nullptr;
    if (length < kPhotoshopBytes + 4) return "its Photoshop segment is cut short";
    if (std::memcmp(data + kPhotoshopBytes, "8BIM", 4) != 0) return nullptr;
    if (length < kIptcSizeEnd) return "its Photoshop segment is cut short";
    if (be16(data + kPhotoshopBytes + 4) == kIptcResource &&
        kIptcSizeEnd + be16(data + kIptcSizeEnd - 2) > length)
      return "its Photoshop IPTC block claims more than its APP13 segment holds";
  }
  return nullptr;
}

}  // namespace

void checkJpegMarkerClaims(const std::filesystem::path& path) {
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
    if (const char* what = overrun(code, &bytes[dataStart], dataLength))
      fail(path, std::string("corrupt JPEG: ") + what + " (" + std::to_string(dataLength) + " bytes)");
    position += 2 + length;
  }
}

}  // namespace spindrift
