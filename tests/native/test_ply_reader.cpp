// The PLY files read here are written by tests/data/make_ply_files.py, with Python's struct module alone.

#include <cmath>
#include <filesystem>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "io/ParticleFile.h"
#include "spindrift/Error.h"

namespace spindrift {
namespace {

std::filesystem::path plyFile(const std::string& name) {
  return std::filesystem::path(SPINDRIFT_TEST_DATA_DIR) / "ply" / name;
}

// The message of the Error that reading `name` throws, or "" when it reads without one.
std::string readPlyError(const std::string& name) {
  try {
    readPly(plyFile(name));
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

void expectVec3(const glm::vec3& actual, float x, float y, float z) {
  EXPECT_FLOAT_EQ(actual.x, x);
  EXPECT_FLOAT_EQ(actual.y, y);
  EXPECT_FLOAT_EQ(actual.z, z);
}

TEST(PlyReader, ReadsAsciiWithEveryAttributeInAnyOrder) {
  const ParticleFileData data = readPly(plyFile("ascii.ply"));
  ASSERT_EQ(data.positions.size(), 3u);
  ASSERT_EQ(data.radii.size(), 3u);
  ASSERT_EQ(data.typeFlags.size(), 3u);
  ASSERT_EQ(data.life.size(), 3u);
  ASSERT_EQ(data.velocities.size(), 3u);

  expectVec3(data.positions[0], 1.0f, 2.0f, 3.0f);
  expectVec3(data.positions[1], -1.5f, 0.25f, 1000.0f);
  expectVec3(data.positions[2], 0.0f, 0.0f, -2.0f);
  EXPECT_FLOAT_EQ(data.radii[0], 0.05f);
  EXPECT_FLOAT_EQ(data.radii[1], 0.125f);
  EXPECT_FLOAT_EQ(data.radii[2], 0.5f);
  EXPECT_EQ(data.typeFlags[0], 8);
  EXPECT_EQ(data.typeFlags[1], 2);
  EXPECT_EQ(data.typeFlags[2], 4);
  EXPECT_FLOAT_EQ(data.life[0], 12.5f);
  EXPECT_FLOAT_EQ(data.life[1], 0.0f);
  EXPECT_FLOAT_EQ(data.life[2], 7.0f);
  expectVec3(data.velocities[0], 1.0f, 2.0f, -3.0f);
  expectVec3(data.velocities[1], 0.5f, -0.5f, 0.0f);
  expectVec3(data.velocities[2], 0.0f, 0.0f, 1.0f);
}

TEST(PlyReader, ReadsBinaryLittleEndianAndSkipsOtherPropertiesAndElements) {
  const ParticleFileData data = readPly(plyFile("binary_little_endian.ply"));
  ASSERT_EQ(data.positions.size(), 3u);
  ASSERT_EQ(data.radii.size(), 3u);
  ASSERT_EQ(data.typeFlags.size(), 3u);
  EXPECT_TRUE(data.life.empty());
  EXPECT_TRUE(data.velocities.empty());

  expectVec3(data.positions[0], 0.1f, 0.2f, 0.3f);
  expectVec3(data.positions[1], -1.0f, 2.5f, 1.0e6f);
  expectVec3(data.positions[2], 4.0f, -4.0f, 0.0f);
  EXPECT_FLOAT_EQ(data.radii[0], 0.5f);
  EXPECT_FLOAT_EQ(data.radii[1], 0.25f);
  EXPECT_FLOAT_EQ(data.radii[2], 1.5f);
  EXPECT_EQ(data.typeFlags[0], 8);
  EXPECT_EQ(data.typeFlags[1], 2);
  EXPECT_EQ(data.typeFlags[2], 0);
}

TEST(PlyReader, ReadsBinaryBigEndianWithTypeAliasesPscaleAndVelocities) {
  const ParticleFileData data = readPly(plyFile("binary_big_endian.ply"));
  ASSERT_EQ(data.positions.size(), 2u);
  ASSERT_EQ(data.radii.size(), 2u);
  ASSERT_EQ(data.typeFlags.size(), 2u);
  ASSERT_EQ(data.life.size(), 2u);
  ASSERT_EQ(data.velocities.size(), 2u);

  expectVec3(data.positions[0], 1.0f, 2.0f, 3.0f);
  expectVec3(data.positions[1], -8.0f, 0.0f, 0.5f);
  EXPECT_FLOAT_EQ(data.radii[0], 0.75f);
  EXPECT_FLOAT_EQ(data.radii[1], 0.0625f);
  EXPECT_EQ(data.typeFlags[0], 4);
  EXPECT_EQ(data.typeFlags[1], -1);
  EXPECT_FLOAT_EQ(data.life[0], 30.0f);
  EXPECT_FLOAT_EQ(data.life[1], 65535.0f);
  expectVec3(data.velocities[0], 0.5f, -0.5f, 2.0f);
  expectVec3(data.velocities[1], 0.0f, 0.0f, -9.5f);
}

TEST(PlyReader, KeepsNonFinitePositionsForTheSceneToDrop) {
  const ParticleFileData data = readPly(plyFile("non_finite.ply"));
  ASSERT_EQ(data.positions.size(), 4u);
  EXPECT_TRUE(std::isnan(data.positions[0].x));
  EXPECT_TRUE(std::isinf(data.positions[1].y) && data.positions[1].y > 0.0f);
  EXPECT_TRUE(std::isinf(data.positions[2].z) && data.positions[2].z < 0.0f);
  expectVec3(data.positions[3], 1.0f, 1.0f, 1.0f);
  EXPECT_TRUE(data.radii.empty());
}

TEST(PlyReader, PrefersRadiusOverPscale) {
  const ParticleFileData data = readPly(plyFile("pscale_and_radius.ply"));
  ASSERT_EQ(data.radii.size(), 1u);
  EXPECT_FLOAT_EQ(data.radii[0], 0.5f);
  expectVec3(data.positions[0], 1.0f, 2.0f, 3.0f);
}

TEST(PlyReader, ReadsAsciiWithoutAFinalLineEnd) {
  const ParticleFileData data = readPly(plyFile("no_final_line_end.ply"));
  ASSERT_EQ(data.positions.size(), 2u);
  expectVec3(data.positions[1], 1.0f, 2.0f, 3.0f);
}

TEST(PlyReader, ReadsAFileWithNoVertices) {
  const ParticleFileData data = readPly(plyFile("empty.ply"));
  EXPECT_EQ(data.positions.size(), 0u);
}

struct MalformedCase {
  const char* file;
  const char* expectedWords;  // A part of the message that says what is wrong.
};

// Names the case by its file in test output and CTest names, instead of gtest's byte dump.
void PrintTo(const MalformedCase& malformed, std::ostream* stream) {
  *stream << malformed.file;
}

class PlyReaderMalformed : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(PlyReaderMalformed, ThrowsOneLineNamingTheFileAndTheProblem) {
  const MalformedCase& malformed = GetParam();
  const std::string message = readPlyError(malformed.file);
  ASSERT_FALSE(message.empty()) << malformed.file << " was read without an error";
  EXPECT_NE(message.find(plyFile(malformed.file).string()), std::string::npos) << message;
  EXPECT_NE(message.find(malformed.expectedWords), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    Files, PlyReaderMalformed,
    ::testing::Values(MalformedCase{"truncated_binary.ply", "truncated"},
                      MalformedCase{"truncated_face_list.ply", "truncated"},
                      MalformedCase{"missing_y.ply", "no 'y' property"},
                      MalformedCase{"bad_format.ply", "unknown format 'binary_middle_endian'"},
                      MalformedCase{"absurd_count.ply", "declares 1000000000000 vertex rows"},
                      MalformedCase{"ascii_extra_rows.ply", "more than the header's element counts"},
                      MalformedCase{"ascii_short_row.ply", "too few values"},
                      MalformedCase{"binary_extra_bytes.ply", "do not match"},
                      MalformedCase{"no_end_header.ply", "no end_header"},
                      MalformedCase{"not_ply.ply", "not a PLY file"},
                      MalformedCase{"unknown_type.ply", "unknown property type"},
                      MalformedCase{"no_vertex.ply", "no vertex element"},
                      MalformedCase{"does_not_exist.ply", "cannot open"}),
    [](const ::testing::TestParamInfo<MalformedCase>& info) {
      std::string name = info.param.file;
      name = name.substr(0, name.find('.'));
      return name;
    });

}  // namespace
}  // namespace spindrift
