#pragma once

// The header of a PLY file, parsed: shared by the reader and nothing else, so it lives beside it.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace spindrift::ply {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

enum class ScalarType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct PlyProperty {
  std::string name;
  ScalarType valueType = ScalarType::Float32;
  bool isList = false;
  ScalarType listCountType = ScalarType::UInt8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
};

/// Throws Error with "<path>: <what>".
[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what);

std::size_t scalarSize(ScalarType type);

/// The whitespace-separated words of one line.
std::vector<std::string> splitWords(std::string_view line);

/// Reads the header from the start of `bytes`; `bodyOffset` is set to the first byte after the
/// `end_header` line. Throws Error naming `path` when the header is malformed.
PlyHeader parseHeader(const std::filesystem::path& path, const std::vector<char>& bytes,
                      std::size_t* bodyOffset);

}  // namespace spindrift::ply
