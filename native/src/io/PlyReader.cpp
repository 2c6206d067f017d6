#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include "io/ParticleFile.h"
#include "io/PlyHeader.h"
#include "spindrift/Error.h"
#include "spindrift/Limits.h"

namespace spindrift {
namespace {

using ply::fail;
using ply::PlyElement;
using ply::PlyFormat;
using ply::PlyHeader;
using ply::PlyProperty;
using ply::scalarSize;
using ply::ScalarType;

// Where each attribute of ParticleFileData comes from in the vertex element: property indices, or -1.
struct VertexLayout {
  int x = -1, y = -1, z = -1;
  int radius = -1;
  int type = -1;
  int life = -1;
  int vx = -1, vy = -1, vz = -1;
};

VertexLayout findVertexLayout(const std::filesystem::path& path, const PlyElement& vertex) {
  VertexLayout layout;
  int pscale = -1;
  const std::array<std::pair<const char*, int*>, 10> wanted = {{{"x", &layout.x},
                                                                {"y", &layout.y},
                                                                {"z", &layout.z},
                                                                {"radius", &layout.radius},
                                                                {"pscale", &pscale},
                                                                {"type", &layout.type},
                                                                {"life", &layout.life},
                                                                {"vx", &layout.vx},
                                                                {"vy", &layout.vy},
                                                                {"vz", &layout.vz}}};
  for (int index = 0; index < int(vertex.properties.size()); ++index) {
    const PlyProperty& property = vertex.properties[index];
    int* slot = nullptr;
    for (const auto& [name, target] : wanted) {
      if (property.name == name) slot = target;
    }
    if (slot == nullptr) continue;
    if (property.isList) fail(path, "vertex property '" + property.name + "' is a list, expected a number");
    *slot = index;
  }
  for (const auto& [name, index] : {std::pair{"x", layout.x}, {"y", layout.y}, {"z", layout.z}}) {
    if (index < 0) fail(path, std::string("vertex element has no '") + name + "' property");
  }
  // `radius` is the PLY convention and wins over Houdini's `pscale` when a file has both.
  if (layout.radius < 0) layout.radius = pscale;
  const int velocityComponents = (layout.vx >= 0) + (layout.vy >= 0) + (layout.vz >= 0);
  if (velocityComponents != 0 && velocityComponents != 3) {
    fail(path, "vertex element has only some of 'vx vy vz'");
  }
  return layout;
}

// Sequential, bounds-checked access to the binary body.
class BinaryCursor {
 public:
  BinaryCursor(const std::filesystem::path& path, const std::vector<char>& bytes, std::size_t offset,
               bool swapBytes)
      : path_(path), bytes_(bytes), offset_(offset), swapBytes_(swapBytes) {}

  std::size_t remaining() const { return bytes_.size() - offset_; }
  std::size_t offset() const { return offset_; }

  double read(ScalarType type, const std::string& elementName, std::uint64_t row) {
    const std::size_t size = scalarSize(type);
    if (size > remaining()) {
      fail(path_, "truncated binary data in element '" + elementName + "' at row " + std::to_string(row));
    }
    unsigned char raw[8];
    std::memcpy(raw, bytes_.data() + offset_, size);
    offset_ += size;
    if (swapBytes_) std::reverse(raw, raw + size);
    return decode(type, raw);
  }

 private:
  static double decode(ScalarType type, const unsigned char* raw) {
    switch (type) {
      case ScalarType::Int8:
        return load<std::int8_t>(raw);
      case ScalarType::UInt8:
        return load<std::uint8_t>(raw);
      case ScalarType::Int16:
        return load<std::int16_t>(raw);
      case ScalarType::UInt16:
        return load<std::uint16_t>(raw);
      case ScalarType::Int32:
        return load<std::int32_t>(raw);
      case ScalarType::UInt32:
        return load<std::uint32_t>(raw);
      case ScalarType::Float32:
        return load<float>(raw);
      case ScalarType::Float64:
        return load<double>(raw);
    }
    return 0.0;
  }

  template <typename T>
  static double load(const unsigned char* raw) {
    T value;
    std::memcpy(&value, raw, sizeof(T));
    return static_cast<double>(value);
  }

  const std::filesystem::path& path_;
  const std::vector<char>& bytes_;
  std::size_t offset_;
  bool swapBytes_;
};

// Sequential access to the lines of the ASCII body; each element row is one line.
class AsciiCursor {
 public:
  AsciiCursor(const std::vector<char>& bytes, std::size_t offset) : bytes_(bytes), offset_(offset) {}

  // The words of the next non-empty line, or false at the end of the file.
  bool nextRow(std::vector<std::string>* words) {
    while (offset_ < bytes_.size()) {
      const char* begin = bytes_.data() + offset_;
      const void* newline = std::memchr(begin, '\n', bytes_.size() - offset_);
      const std::size_t length =
          newline ? static_cast<const char*>(newline) - begin : bytes_.size() - offset_;
      offset_ += length + (newline ? 1 : 0);
      ++lineNumber_;
      *words = ply::splitWords(std::string_view(begin, length));
      if (!words->empty()) return true;
    }
    return false;
  }

  int lineNumber() const { return lineNumber_; }

 private:
  const std::vector<char>& bytes_;
  std::size_t offset_;
  int lineNumber_ = 0;
};

bool parseAsciiNumber(const std::string& word, double* value) {
  char* end = nullptr;
  *value = std::strtod(word.c_str(), &end);
  return end != word.c_str() && *end == '\0';
}

// The smallest number of bytes one row of `element` can take, used to reject counts the file cannot hold
// before anything is allocated.
std::size_t minimumRowBytes(const PlyElement& element, PlyFormat format) {
  std::size_t bytes = 0;
  for (const PlyProperty& property : element.properties) {
    if (format == PlyFormat::Ascii) {
      bytes += 2;  // One digit and one separator (a space, or the line end).
    } else {
      bytes += property.isList ? scalarSize(property.listCountType) : scalarSize(property.valueType);
    }
  }
  return bytes;
}

bool hostIsLittleEndian() {
  const std::uint16_t probe = 1;
  unsigned char firstByte;
  std::memcpy(&firstByte, &probe, 1);
  return firstByte == 1;
}

void storeVertex(const VertexLayout& layout, const std::vector<double>& values, ParticleFileData* data,
                 const std::filesystem::path& path, std::uint64_t row) {
  data->positions.emplace_back(values[layout.x], values[layout.y], values[layout.z]);
  if (layout.radius >= 0) data->radii.push_back(static_cast<float>(values[layout.radius]));
  if (layout.type >= 0) {
    const double flag = values[layout.type];
    if (!(flag >= std::numeric_limits<std::int32_t>::min() &&
          flag <= std::numeric_limits<std::int32_t>::max())) {
      fail(path, "vertex " + std::to_string(row) + " has type " + std::to_string(flag) + ", not an integer");
    }
    data->typeFlags.push_back(static_cast<std::int32_t>(std::lround(flag)));
  }
  if (layout.life >= 0) data->life.push_back(static_cast<float>(values[layout.life]));
  if (layout.vx >= 0) data->velocities.emplace_back(values[layout.vx], values[layout.vy], values[layout.vz]);
}

void reserveVertices(const VertexLayout& layout, std::size_t count, ParticleFileData* data) {
  data->positions.reserve(count);
  if (layout.radius >= 0) data->radii.reserve(count);
  if (layout.type >= 0) data->typeFlags.reserve(count);
  if (layout.life >= 0) data->life.reserve(count);
  if (layout.vx >= 0) data->velocities.reserve(count);
}

void readAsciiBody(const std::filesystem::path& path, const std::vector<char>& bytes, std::size_t bodyOffset,
                   const PlyHeader& header, const PlyElement* vertexElement, const VertexLayout& layout,
                   ParticleFileData* data) {
  std::vector<double> values;
  AsciiCursor cursor(bytes, bodyOffset);
  std::vector<std::string> words;
  for (const PlyElement& element : header.elements) {
    const bool isVertex = &element == vertexElement;
    for (std::uint64_t row = 0; row < element.count; ++row) {
      if (!cursor.nextRow(&words)) {
        fail(path, "truncated: element '" + element.name + "' declares " + std::to_string(element.count) +
                       " rows, the file ends after " + std::to_string(row));
      }
      // Built only for a message: a per-row string would dominate the time of large files.
      const auto where = [&] {
        return "line " + std::to_string(cursor.lineNumber()) + " of the data (" + element.name + " " +
               std::to_string(row) + "): ";
      };
      values.assign(element.properties.size(), 0.0);
      std::size_t wordIndex = 0;
      for (std::size_t index = 0; index < element.properties.size(); ++index) {
        const PlyProperty& property = element.properties[index];
        double listLength = 1.0;
        if (property.isList) {
          if (wordIndex >= words.size() || !parseAsciiNumber(words[wordIndex++], &listLength) ||
              !(listLength >= 0.0) || listLength != std::floor(listLength)) {
            fail(path, where() + "bad list length for '" + property.name + "'");
          }
        }
        if (listLength > double(words.size() - wordIndex)) fail(path, where() + "too few values");
        for (std::size_t item = 0; item < std::size_t(listLength); ++item) {
          if (!parseAsciiNumber(words[wordIndex++], &values[index])) {
            fail(path, where() + "'" + words[wordIndex - 1] + "' is not a number");
          }
        }
      }
      if (wordIndex != words.size()) {
        fail(path, where() + std::to_string(words.size()) + " values, expected " + std::to_string(wordIndex));
      }
      if (isVertex) storeVertex(layout, values, data, path, row);
    }
  }
  if (cursor.nextRow(&words)) {
    fail(path, "line " + std::to_string(cursor.lineNumber()) +
                   " of the data is more than the header's element counts declare");
  }
}

void readBinaryBody(const std::filesystem::path& path, const std::vector<char>& bytes, std::size_t bodyOffset,
                    const PlyHeader& header, const PlyElement* vertexElement, const VertexLayout& layout,
                    ParticleFileData* data) {
  std::vector<double> values;
  const bool fileIsLittleEndian = header.format == PlyFormat::BinaryLittleEndian;
  BinaryCursor cursor(path, bytes, bodyOffset, fileIsLittleEndian != hostIsLittleEndian());
  for (const PlyElement& element : header.elements) {
    const bool isVertex = &element == vertexElement;
    values.assign(element.properties.size(), 0.0);
    for (std::uint64_t row = 0; row < element.count; ++row) {
      for (std::size_t index = 0; index < element.properties.size(); ++index) {
        const PlyProperty& property = element.properties[index];
        if (!property.isList) {
          values[index] = cursor.read(property.valueType, element.name, row);
          continue;
        }
        const double listLength = cursor.read(property.listCountType, element.name, row);
        if (listLength < 0.0) fail(path, "negative list length in element '" + element.name + "'");
        const std::size_t itemSize = scalarSize(property.valueType);
        if (listLength > double(cursor.remaining() / itemSize)) {
          fail(path, "truncated binary data in element '" + element.name + "' at row " + std::to_string(row));
        }
        for (std::size_t item = 0; item < std::size_t(listLength); ++item) {
          cursor.read(property.valueType, element.name, row);
        }
      }
      if (isVertex) storeVertex(layout, values, data, path, row);
    }
  }
  if (cursor.remaining() != 0) {
    fail(path, std::to_string(cursor.remaining()) +
                   " bytes follow the last element: the header's element counts do not match the data");
  }
}

}  // namespace

ParticleFileData readPly(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) fail(path, "cannot open PLY file");
  std::error_code sizeError;
  const std::uintmax_t fileSize = std::filesystem::file_size(path, sizeError);
  if (sizeError) fail(path, "cannot read PLY file: " + sizeError.message());
  requireMemory(std::uint64_t(fileSize), path.string() + ": reading the file");
  std::vector<char> bytes(static_cast<std::size_t>(fileSize));
  if (!file.read(bytes.data(), static_cast<std::streamsize>(bytes.size()))) {
    fail(path, "cannot read PLY file");
  }

  std::size_t bodyOffset = 0;
  const PlyHeader header = ply::parseHeader(path, bytes, &bodyOffset);
  const auto vertexElement = std::find_if(header.elements.begin(), header.elements.end(),
                                          [](const PlyElement& element) { return element.name == "vertex"; });
  if (vertexElement == header.elements.end()) fail(path, "PLY file has no vertex element");
  const VertexLayout layout = findVertexLayout(path, *vertexElement);

  const std::size_t bodyBytes = bytes.size() - bodyOffset;
  // The last ASCII row may lack its line end.
  const std::size_t bytesForRows = bodyBytes + (header.format == PlyFormat::Ascii ? 1 : 0);
  for (const PlyElement& element : header.elements) {
    const std::size_t rowBytes = std::max<std::size_t>(1, minimumRowBytes(element, header.format));
    if (element.count > bytesForRows / rowBytes) {
      fail(path, "truncated, or a wrong count: the header declares " + std::to_string(element.count) + " " +
                     element.name + " rows, more than the " + std::to_string(bodyBytes) +
                     " bytes of data can hold");
    }
  }

  // Up to nine floats per vertex (position, radius, type, life, velocity) come out of the file.
  requireMemory(std::uint64_t(vertexElement->count) * 9 * sizeof(float),
                path.string() + ": the vertex arrays");
  ParticleFileData data;
  reserveVertices(layout, static_cast<std::size_t>(vertexElement->count), &data);
  if (header.format == PlyFormat::Ascii) {
    readAsciiBody(path, bytes, bodyOffset, header, &*vertexElement, layout, &data);
  } else {
    readBinaryBody(path, bytes, bodyOffset, header, &*vertexElement, layout, &data);
  }
  return data;
}

}  // namespace spindrift
