#include "io/PlyHeader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <utility>

#include "spindrift/Error.h"

namespace spindrift::ply {
namespace {

// A header longer than this is not a particle file; the limit keeps a binary file without `end_header`
// from being read line by line to its end.
constexpr std::size_t kMaxHeaderBytes = 1 << 20;

bool parseScalarType(const std::string& name, ScalarType* type) {
  static const std::array<std::pair<const char*, ScalarType>, 16> kNames = {{
      {"char", ScalarType::Int8},
      {"int8", ScalarType::Int8},
      {"uchar", ScalarType::UInt8},
      {"uint8", ScalarType::UInt8},
      {"short", ScalarType::Int16},
      {"int16", ScalarType::Int16},
      {"ushort", ScalarType::UInt16},
      {"uint16", ScalarType::UInt16},
      {"int", ScalarType::Int32},
      {"int32", ScalarType::Int32},
      {"uint", ScalarType::UInt32},
      {"uint32", ScalarType::UInt32},
      {"float", ScalarType::Float32},
      {"float32", ScalarType::Float32},
      {"double", ScalarType::Float64},
      {"float64", ScalarType::Float64},
  }};
  for (const auto& [typeName, value] : kNames) {
    if (name == typeName) {
      *type = value;
      return true;
    }
  }
  return false;
}

bool isIntegerType(ScalarType type) {
  return type != ScalarType::Float32 && type != ScalarType::Float64;
}

bool parseCount(const std::string& text, std::uint64_t* count) {
  if (text.empty() || text.size() > 19) return false;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
  }
  *count = std::stoull(text);
  return true;
}

}  // namespace

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
  throw Error(path.string() + ": " + what);
}

std::size_t scalarSize(ScalarType type) {
  switch (type) {
    case ScalarType::Int8:
    case ScalarType::UInt8:
      return 1;
    case ScalarType::Int16:
    case ScalarType::UInt16:
      return 2;
    case ScalarType::Int32:
    case ScalarType::UInt32:
    case ScalarType::Float32:
      return 4;
    case ScalarType::Float64:
      return 8;
  }
  return 1;
}

std::vector<std::string> splitWords(std::string_view line) {
  std::vector<std::string> words;
  std::size_t position = 0;
  while (position < line.size()) {
    while (position < line.size() && std::isspace(static_cast<unsigned char>(line[position]))) {
      ++position;
    }
    std::size_t end = position;
    while (end < line.size() && !std::isspace(static_cast<unsigned char>(line[end]))) {
      ++end;
    }
    if (end > position) words.emplace_back(line.substr(position, end - position));
    position = end;
  }
  return words;
}

PlyHeader parseHeader(const std::filesystem::path& path, const std::vector<char>& bytes,
                      std::size_t* bodyOffset) {
  PlyHeader header;
  bool sawFormat = false;
  std::size_t position = 0;
  int lineNumber = 0;
  const std::size_t headerLimit = std::min(bytes.size(), kMaxHeaderBytes);
  while (true) {
    const char* begin = bytes.data() + position;
    const void* newline = position < headerLimit ? std::memchr(begin, '\n', headerLimit - position) : nullptr;
    if (newline == nullptr) fail(path, "bad PLY header: no end_header line");
    const std::size_t lineLength = static_cast<const char*>(newline) - begin;
    std::string_view line(begin, lineLength);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    position += lineLength + 1;
    ++lineNumber;
    const std::vector<std::string> words = splitWords(line);
    const std::string where = "bad PLY header, line " + std::to_string(lineNumber) + ": ";

    if (lineNumber == 1) {
      if (words.size() != 1 || words[0] != "ply") fail(path, "not a PLY file (it does not start with 'ply')");
      continue;
    }
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "end_header") break;
    if (words[0] == "format") {
      if (words.size() != 3) fail(path, where + "expected 'format <type> 1.0'");
      if (words[1] == "ascii") {
        header.format = PlyFormat::Ascii;
      } else if (words[1] == "binary_little_endian") {
        header.format = PlyFormat::BinaryLittleEndian;
      } else if (words[1] == "binary_big_endian") {
        header.format = PlyFormat::BinaryBigEndian;
      } else {
        fail(path, where + "unknown format '" + words[1] + "'");
      }
      if (words[2] != "1.0") fail(path, where + "unsupported PLY version '" + words[2] + "'");
      sawFormat = true;
    } else if (words[0] == "element") {
      PlyElement element;
      if (words.size() != 3 || !parseCount(words[2], &element.count)) {
        fail(path, where + "expected 'element <name> <count>'");
      }
      element.name = words[1];
      header.elements.push_back(std::move(element));
    } else if (words[0] == "property") {
      if (header.elements.empty()) fail(path, where + "property before any element");
      PlyProperty property;
      bool typesKnown = false;
      if (words.size() == 5 && words[1] == "list") {
        property.isList = true;
        property.name = words[4];
        typesKnown = parseScalarType(words[2], &property.listCountType) &&
                     parseScalarType(words[3], &property.valueType) && isIntegerType(property.listCountType);
      } else if (words.size() == 3) {
        property.name = words[2];
        typesKnown = parseScalarType(words[1], &property.valueType);
      } else {
        fail(path, where + "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
      }
      if (!typesKnown) fail(path, where + "unknown property type in '" + std::string(line) + "'");
      for (const PlyProperty& existing : header.elements.back().properties) {
        if (existing.name == property.name) fail(path, where + "property '" + property.name + "' repeated");
      }
      header.elements.back().properties.push_back(std::move(property));
    } else {
      fail(path, where + "unexpected keyword '" + words[0] + "'");
    }
  }
  if (!sawFormat) fail(path, "bad PLY header: no format line");
  *bodyOffset = position;
  return header;
}

}  // namespace spindrift::ply
