#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <openvdb/openvdb.h>
#include <openvdb/points/PointDataGrid.h>
#include <unistd.h>

#include "BlenderReference.h"
#include "io/ParticleFile.h"
#include "spindrift/Error.h"

namespace spindrift {
namespace {

namespace fs = std::filesystem;
using openvdb::points::TruncateCodec;
using openvdb::points::TypedAttributeArray;

/// The message of the Error that `read` throws, or a test failure when it throws none or another kind.
template <typename Read>
std::string errorMessage(Read read) {
  try {
    read();
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected spindrift::Error";
  return {};
}

fs::path scratchDirectory() {
  const fs::path directory =
      fs::temp_directory_path() / ("spindrift_vdb_errors_" + std::to_string(::getpid()));
  fs::create_directories(directory);
  return directory;
}

std::string liquidFile() {
  const nlohmann::json& frames = test::blenderReference().at("fluid").at("domains").at(0).at("frames");
  return frames.begin().value().at("files").at("liquid");
}

TEST(VdbPointReaderErrors, MissingFileIsNamed) {
  const std::string path = (scratchDirectory() / "absent.vdb").string();
  const std::string message = errorMessage([&] { readVdbPoints(path, ""); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

TEST(VdbPointReaderErrors, FileThatIsNotAVdbIsNamed) {
  const fs::path path = scratchDirectory() / "not_a.vdb";
  std::ofstream(path) << "ply\nformat ascii 1.0\nend_header\n";
  const std::string message = errorMessage([&] { readVdbPoints(path, ""); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
}

TEST(VdbPointReaderErrors, WrongGridNameListsTheGrids) {
  const std::string path = liquidFile();
  const std::string message = errorMessage([&] { readVdbPoints(path, "foam"); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("'foam'"), std::string::npos) << message;
  // Mantaflow's liquid data file holds the point grid and the velocity grid.
  EXPECT_NE(message.find("'particles'"), std::string::npos) << message;
  EXPECT_NE(message.find("'velocity'"), std::string::npos) << message;
}

TEST(VdbPointReaderErrors, NamedGridThatHoldsNoPointsIsRefused) {
  const std::string message = errorMessage([&] { readVdbPoints(liquidFile(), "velocity"); });
  EXPECT_NE(message.find("not a point grid"), std::string::npos) << message;
}

TEST(VdbPointReaderErrors, FileWithoutPointGridIsRefused) {
  openvdb::initialize();
  const fs::path path = scratchDirectory() / "density.vdb";
  openvdb::FloatGrid::Ptr density = openvdb::FloatGrid::create();
  density->setName("density");
  density->tree().setValue(openvdb::Coord(1, 2, 3), 1.0f);
  openvdb::io::File(path.string()).write({density});
  const std::string message = errorMessage([&] { readVdbPoints(path, ""); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("'density'"), std::string::npos) << message;
}

TEST(VdbPointReaderErrors, UnregisteredAttributeTypeIsAnErrorNotACrash) {
  // The reader registers int32 TruncateCodec once; taking it away again stands in for any attribute type that
  // the reader does not know.
  readVdbPoints(liquidFile(), "particles");
  using Int32Truncated = TypedAttributeArray<std::int32_t, TruncateCodec>;
  Int32Truncated::unregisterType();
  const std::string message = errorMessage([&] { readVdbPoints(liquidFile(), "particles"); });
  Int32Truncated::registerType();
  EXPECT_NE(message.find(liquidFile()), std::string::npos) << message;
  EXPECT_NE(message.find("int32_trnc"), std::string::npos) << message;
}

TEST(VdbPointReaderErrors, EmptyPointGridGivesNoPoints) {
  openvdb::initialize();
  const fs::path path = scratchDirectory() / "empty_points.vdb";
  openvdb::points::PointDataGrid::Ptr grid = openvdb::points::PointDataGrid::create();
  grid->setName("points");
  openvdb::io::File(path.string()).write({grid});
  EXPECT_TRUE(readVdbPoints(path, "").positions.empty());
  EXPECT_TRUE(readVdbPoints(path, "points").positions.empty());
}

}  // namespace
}  // namespace spindrift
