#include "io/ExrHeaderCheck.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/ImageFileErrors.h"
#include "spindrift/Limits.h"

namespace spindrift {
namespace {

using image_file_errors::fail;

// OpenEXR's layout (openexr.com, "OpenEXR File Layout"): magic, version and flags, then one header (several,
// ended by an empty one, in a multi-part file) of attributes `name\0 type\0 int32 size, value`, each header
// ended by an empty name. All integers are little-endian.
constexpr std::uint32_t kMagic = 20000630;
constexpr std::uint32_t kTiledFlag = 0x200;
constexpr std::uint32_t kMultipartFlag = 0x1000;
constexpr std::uint32_t kLongNamesFlag = 0x400;
// Names and type names with their terminator: 31 characters, or 255 with the long-names flag. OpenEXR reads a
// name that runs past its limit as its first bytes and goes on from there, so it parses a different header
// from here on than a check that read the whole name would (fuzz_background_image: a 90-character name made
// the next bytes a 1.8 GB attribute size).
constexpr std::size_t kMaxShortNameBytes = 32;
constexpr std::size_t kMaxLongNameBytes = 256;
// OpenEXR reads an attribute's value by its type, not by the size the header gives it (ImfHeader.cpp: each
// type's readValueFrom): a box2i is 16 bytes whatever its size says, and a channel list runs to its empty
// name. Where the two differ OpenEXR goes on parsing from another byte than the size leads to, so the check
// would see another header than OpenEXR (fuzz_background_image: a channel list longer than its size hid a
// 1.6 GB string from the check). Such a header is refused.
std::optional<std::uint32_t> fixedValueBytes(const std::string& type) {
  static const std::pair<const char*, std::uint32_t> kFixed[] = {
      {"box2i", 16},      {"box2f", 16},   {"chromaticities", 32},
      {"compression", 1}, {"double", 8},   {"envmap", 1},
      {"float", 4},       {"int", 4},      {"keycode", 28},
      {"lineOrder", 1},   {"m33f", 36},    {"m33d", 72},
      {"m44f", 64},       {"m44d", 128},   {"rational", 8},
      {"tiledesc", 9},    {"timecode", 8}, {"v2i", 8},
      {"v2f", 8},         {"v2d", 16},     {"v3i", 12},
      {"v3f", 12},        {"v3d", 24},     {"deepImageState", 1}};
  for (const auto& [name, bytes] : kFixed)
    if (type == name) return bytes;
  return std::nullopt;
}

// Headers are a few kilobytes; a larger one is read only this far, and its claims beyond are not checked.
constexpr std::size_t kMaxHeaderBytes = std::size_t(16) << 20;

// Reads the file's first bytes as they are needed: 64 KiB, doubled while a header goes on, up to 16 MiB.
class HeaderReader {
 public:
  HeaderReader(const std::filesystem::path& path, std::uint64_t fileSize)
      : path_(path), file_(path, std::ios::binary), fileSize_(fileSize) {}

  std::size_t position() const { return position_; }
  std::uint64_t bytesLeft() const { return fileSize_ - position_; }

  // Returns nothing when the header goes on beyond what is checked, or the file cannot be read (OpenImageIO
  // then reports it).
  std::optional<std::string> name(std::size_t maxBytes) {
    for (std::size_t at = position_; at < position_ + maxBytes; ++at) {
      if (!holds(at, 1)) {
        if (!readAll()) return std::nullopt;
        fail(path_, "the OpenEXR header is cut off");
      }
      if (bytes_[at] != 0) continue;
      std::string text(bytes_.begin() + position_, bytes_.begin() + at);
      position_ = at + 1;
      return text;
    }
    fail(path_, "an OpenEXR header name is longer than " + std::to_string(maxBytes - 1) + " characters" +
                    (maxBytes == kMaxShortNameBytes ? " (the file does not set the long-names flag)" : ""));
  }

  std::optional<std::uint32_t> u32() {
    if (!holds(position_, 4)) {
      if (!readAll()) return std::nullopt;
      fail(path_, "the OpenEXR header is cut off");
    }
    const std::uint32_t value = std::uint32_t(i32At(position_));
    position_ += 4;
    return value;
  }

  // Whether bytes [at, at + count) are read, reading more of the file if need be.
  bool holds(std::uint64_t at, std::uint64_t count) {
    while (at + count > bytes_.size()) {
      const std::uint64_t wanted = std::min<std::uint64_t>(
          {std::max<std::uint64_t>(2 * bytes_.size(), 64 << 10), kMaxHeaderBytes, fileSize_});
      if (wanted <= bytes_.size()) return false;
      const std::size_t before = bytes_.size();
      bytes_.resize(std::size_t(wanted));
      if (!file_.read(reinterpret_cast<char*>(bytes_.data() + before), std::streamsize(wanted - before))) {
        bytes_.resize(before);
        failedRead_ = true;
        return false;
      }
    }
    return true;
  }

  std::int32_t i32At(std::size_t at) const {
    return std::int32_t(std::uint32_t(bytes_[at]) | std::uint32_t(bytes_[at + 1]) << 8 |
                        std::uint32_t(bytes_[at + 2]) << 16 | std::uint32_t(bytes_[at + 3]) << 24);
  }
  unsigned char byteAt(std::size_t at) const { return bytes_[at]; }
  void skip(std::uint64_t count) { position_ += std::size_t(count); }

 private:
  // Whether the whole file is read, so that running out of bytes means the header is cut off.
  bool readAll() const { return !failedRead_ && bytes_.size() == fileSize_; }

  std::filesystem::path path_;
  std::ifstream file_;
  std::uint64_t fileSize_;
  std::vector<unsigned char> bytes_;
  std::size_t position_ = 0;
  bool failedRead_ = false;
};

// What one part's header says about its chunks (its offset table has one 8-byte entry per chunk).
struct PartLayout {
  std::int64_t width = 0, height = 0;
  bool tiled = false;
  std::int64_t tileWidth = 0, tileHeight = 0;
  int scanlinesPerChunk = 256;  // the largest any compression uses: the fewest chunks a part can have
  std::optional<std::int64_t> chunkCount;
  std::uint64_t bytesPerPixel = 0;  // of all channels, as stored (half 2, float and uint 4)

  // What OpenEXR allocates to decode one chunk: a scanline chunk's rows, or a tile, at every channel.
  std::uint64_t chunkBytes() const {
    if (width <= 0 || height <= 0) return 0;
    const std::uint64_t pixels = tiled ? std::uint64_t(std::max<std::int64_t>(tileWidth, 0)) *
                                             std::uint64_t(std::max<std::int64_t>(tileHeight, 0))
                                       : std::uint64_t(width) * std::uint64_t(scanlinesPerChunk);
    return pixels * bytesPerPixel;
  }

  std::int64_t fewestChunks() const {
    if (chunkCount) return *chunkCount;
    if (width <= 0 || height <= 0) return 0;  // OpenEXR refuses such a window itself
    if (tiled) {
      if (tileWidth <= 0 || tileHeight <= 0) return 0;
      return ((width + tileWidth - 1) / tileWidth) * ((height + tileHeight - 1) / tileHeight);
    }
    return (height + scanlinesPerChunk - 1) / scanlinesPerChunk;
  }
};

int scanlinesPerChunk(unsigned compression) {
  switch (compression) {
    case 0:
    case 1:
    case 2:
      return 1;  // none, RLE, ZIPS
    case 3:
    case 5:
      return 16;  // ZIP, PXR24
    case 4:
    case 6:
    case 7:
    case 8:
      return 32;  // PIZ, B44, B44A, DWAA
    default:
      return 256;  // DWAB, and the largest for anything newer
  }
}

// Where OpenEXR's reading of a channel list that starts at `at` ends: entries of a name of at most 255
// characters and its terminator, then 16 bytes, until an empty name. Nothing when the file ends first.
std::optional<std::uint64_t> channelListEnd(HeaderReader& reader, std::uint64_t at) {
  constexpr std::uint64_t kMaxChannelNameBytes = 256;
  for (;;) {
    std::uint64_t end = at;
    for (;; ++end) {
      if (!reader.holds(end, 1)) return std::nullopt;
      if (reader.byteAt(std::size_t(end)) == 0) break;
      if (end + 1 - at >= kMaxChannelNameBytes) return end + 1;  // OpenEXR stops reading the name here
    }
    if (end == at) return end + 1;
    at = end + 1 + 16;
  }
}

// OpenEXR reads a string list as (int32 length, bytes) pairs while it has read less than the attribute's
// size, and allocates each string's claimed length before reading it: every string must lie inside the
// attribute.
void requireStringsInside(HeaderReader& reader, const std::filesystem::path& path, const std::string& name,
                          std::uint64_t at, std::uint32_t size) {
  const std::uint64_t end = at + size;
  while (at < end) {
    if (!reader.holds(at, 4)) return;  // past what is checked, or cut off: OpenEXR reports it
    const std::int32_t length = reader.i32At(std::size_t(at));
    if (length < 0 || at + 4 + std::uint64_t(length) > end) {
      fail(path, "the OpenEXR header's string list \"" + name + "\" holds a string of " +
                     std::to_string(length) + " bytes, past the end of its " + std::to_string(size) +
                     "-byte attribute");
    }
    at += 4 + std::uint64_t(length);
  }
}

// Records what `layout` needs from one attribute whose value starts at `at` and is `size` bytes long.
void noteAttribute(HeaderReader& reader, const std::string& name, const std::string& type, std::size_t at,
                   std::uint32_t size, PartLayout* layout) {
  if (name == "dataWindow" && type == "box2i" && size == 16 && reader.holds(at, size)) {
    layout->width = std::int64_t(reader.i32At(at + 8)) - reader.i32At(at) + 1;
    layout->height = std::int64_t(reader.i32At(at + 12)) - reader.i32At(at + 4) + 1;
  } else if (name == "tiles" && type == "tiledesc" && size >= 8 && reader.holds(at, 8)) {
    layout->tiled = true;
    layout->tileWidth = std::uint32_t(reader.i32At(at));
    layout->tileHeight = std::uint32_t(reader.i32At(at + 4));
  } else if (name == "compression" && type == "compression" && size == 1 && reader.holds(at, 1)) {
    layout->scanlinesPerChunk = scanlinesPerChunk(reader.byteAt(at));
  } else if (name == "chunkCount" && type == "int" && size == 4 && reader.holds(at, 4)) {
    layout->chunkCount = std::max(0, reader.i32At(at));
  } else if (name == "channels" && type == "chlist" && reader.holds(at, size)) {
    // Entries of name\0, int32 pixel type, 4 bytes, int32 x and y sampling; an empty name ends the list.
    std::size_t entry = at;
    while (entry < at + size && reader.byteAt(entry) != 0) {
      std::size_t end = entry;
      while (end < at + size && reader.byteAt(end) != 0)
        ++end;
      if (end + 17 > at + size) break;
      layout->bytesPerPixel += reader.i32At(end + 1) == 1 ? 2 : 4;
      entry = end + 17;
    }
  } else if (name == "type" && type == "string" && size >= 1 && reader.holds(at, 1)) {
    layout->tiled = layout->tiled || reader.byteAt(at) == 't';  // "tiledimage" in a multi-part file
  }
}

}  // namespace

void checkExrHeaderClaims(const std::filesystem::path& path) {
  std::error_code error;
  const std::uint64_t fileSize = std::filesystem::file_size(path, error);
  if (error) return;  // OpenImageIO reports what it cannot read
  HeaderReader reader(path, fileSize);
  if (!reader.holds(0, 8)) return;
  if (reader.u32() != kMagic) return;
  const std::uint32_t flags = reader.u32().value_or(0);
  const bool multipart = (flags & kMultipartFlag) != 0;
  const std::size_t maxNameBytes = (flags & kLongNamesFlag) != 0 ? kMaxLongNameBytes : kMaxShortNameBytes;
  std::int64_t chunks = 0;
  for (;;) {
    PartLayout layout;
    layout.tiled = !multipart && (flags & kTiledFlag) != 0;
    int attributes = 0;
    for (;; ++attributes) {
      const std::optional<std::string> name = reader.name(maxNameBytes);
      if (!name) return;
      if (name->empty()) break;
      const std::optional<std::string> type = reader.name(maxNameBytes);
      const std::optional<std::uint32_t> size = type ? reader.u32() : std::nullopt;
      if (!size) return;
      if (std::int32_t(*size) < 0 || *size > reader.bytesLeft()) {
        fail(path, "the OpenEXR header's attribute \"" + *name + "\" claims " +
                       std::to_string(std::int32_t(*size)) + " bytes, and the file has " +
                       std::to_string(reader.bytesLeft()) + " left");
      }
      if (*type == "preview" && reader.holds(reader.position(), 8)) {
        const std::uint64_t pixels = std::uint64_t(std::uint32_t(reader.i32At(reader.position()))) *
                                     std::uint32_t(reader.i32At(reader.position() + 4));
        if (*size < 8 || pixels > (*size - 8) / 4)
          fail(path, "the OpenEXR preview image is larger than its attribute");
      }
      if (const std::optional<std::uint32_t> fixed = fixedValueBytes(*type); fixed && *size != *fixed) {
        fail(path, "the OpenEXR header's attribute \"" + *name + "\" of type " + *type + " claims " +
                       std::to_string(*size) + " bytes, and OpenEXR reads " + std::to_string(*fixed));
      }
      if (*type == "stringvector") requireStringsInside(reader, path, *name, reader.position(), *size);
      if (*type == "chlist") {
        const std::optional<std::uint64_t> end = channelListEnd(reader, reader.position());
        if (end && *end != reader.position() + *size) {
          fail(path, "the OpenEXR header's channel list \"" + *name + "\" claims " + std::to_string(*size) +
                         " bytes, and its entries take " + std::to_string(*end - reader.position()));
        }
      }
      noteAttribute(reader, *name, *type, reader.position(), *size, &layout);
      reader.skip(*size);
    }
    // An empty header ends a multi-part file's list of headers; a single-part file has one header.
    if (multipart && attributes == 0) break;
    chunks += std::min<std::int64_t>(layout.fewestChunks(), std::int64_t(1) << 40);
    if (std::uint64_t(chunks) * 8 > fileSize) {
      fail(path, "the OpenEXR header claims at least " + std::to_string(chunks) +
                     " chunks, more than the file's " + std::to_string(fileSize) + " bytes can index");
    }
    // OpenEXR decodes a chunk into buffers of its whole size before it reads the chunk's bytes: a data window
    // four million pixels wide with a few rows made it zero-fill gigabytes (fuzz_background_image).
    requireMemory(2 * layout.chunkBytes(), path.string() + ": OpenEXR's buffers for one chunk of its pixels");
    if (!multipart) break;
  }
}

}  // namespace spindrift
