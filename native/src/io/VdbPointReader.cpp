#include <algorithm>
#include <cstdint>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/AttributeArray.h>
#include <openvdb/points/PointCount.h>
#include <openvdb/points/PointDataGrid.h>

#include "io/ParticleFile.h"
#include "spindrift/Error.h"
#include "spindrift/Limits.h"

namespace spindrift {
namespace {

using openvdb::points::AttributeHandle;
using openvdb::points::PointDataGrid;
using openvdb::points::TruncateCodec;
using openvdb::points::TypedAttributeArray;

// Mantaflow stores attributes at half precision (Blender's default "Half" OpenVDB depth) with TruncateCodec,
// and openvdb::initialize() does not register the int32 variant: without it reading the grid throws
// "Cannot create attribute of unregistered type int32_trnc".
template <typename Array>
void registerOnce() {
  if (!Array::isRegistered()) Array::registerType();
}

void initializeOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] {
    openvdb::initialize();
    registerOnce<TypedAttributeArray<std::int32_t, TruncateCodec>>();
    registerOnce<TypedAttributeArray<float, TruncateCodec>>();
    registerOnce<TypedAttributeArray<openvdb::Vec3f, TruncateCodec>>();
  });
}

std::string joinNames(const std::vector<std::string>& names) {
  if (names.empty()) return "none";
  std::string joined;
  for (const std::string& name : names)
    joined += (joined.empty() ? "" : ", ") + ("'" + name + "'");
  return joined;
}

// Converts one stored value of attribute NAME. A cast of a NaN or out-of-range floating value to an integer,
// or of a double beyond float's range to float, is undefined behaviour (fuzz_vdb_points found a NaN flag):
// such a flag is a corrupt file and an error naming the attribute; such a float becomes ±infinity, which
// the particle checks downstream treat as any non-finite value.
template <typename Out, typename Stored>
Out convertValue(Stored value, const std::string& name) {
  if constexpr (std::is_integral_v<Out> && std::is_floating_point_v<Stored>) {
    if (!(double(value) >= double(std::numeric_limits<Out>::min()) &&
          double(value) <= double(std::numeric_limits<Out>::max()))) {
      std::ostringstream text;
      text << "attribute '" << name << "' holds " << value << ", not a " << 8 * sizeof(Out) << "-bit integer";
      throw Error(text.str());
    }
  } else if constexpr (std::is_integral_v<Out>) {
    // In long long: every stored integer type (int16, int32, int64) and every Out fit in it.
    if (static_cast<long long>(value) < static_cast<long long>(std::numeric_limits<Out>::min()) ||
        static_cast<long long>(value) > static_cast<long long>(std::numeric_limits<Out>::max()))
      throw Error("attribute '" + name + "' holds " + std::to_string(value) + ", not a " +
                  std::to_string(8 * sizeof(Out)) + "-bit integer");
  } else if constexpr (std::is_floating_point_v<Stored> && sizeof(Stored) > sizeof(Out)) {
    if (value > Stored(std::numeric_limits<Out>::max())) return std::numeric_limits<Out>::infinity();
    if (value < Stored(std::numeric_limits<Out>::lowest())) return -std::numeric_limits<Out>::infinity();
  }
  return Out(value);
}

// Reads a scalar attribute whatever its storage: Mantaflow writes flags as int32 and life as float, but a
// file written at full precision, or by another tool, may use other numeric types.
template <typename Out>
bool readScalar(const PointDataGrid& grid, const std::string& name, std::vector<Out>& values) {
  const auto leaf0 = grid.tree().cbeginLeaf();
  if (!leaf0) return false;
  const std::size_t index = leaf0->attributeSet().find(name);
  if (index == openvdb::points::AttributeSet::INVALID_POS) return false;
  const std::string valueType = leaf0->constAttributeArray(index).valueType();

  auto readAs = [&](auto tag) {
    using Stored = decltype(tag);
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
      const AttributeHandle<Stored> handle(leaf->constAttributeArray(index));
      for (auto point = leaf->beginIndexOn(); point; ++point)
        values.push_back(convertValue<Out>(handle.get(*point), name));
    }
  };
  if (valueType == openvdb::typeNameAsString<std::int32_t>()) {
    readAs(std::int32_t{});
  } else if (valueType == openvdb::typeNameAsString<float>()) {
    readAs(float{});
  } else if (valueType == openvdb::typeNameAsString<double>()) {
    readAs(double{});
  } else if (valueType == openvdb::typeNameAsString<std::int64_t>()) {
    readAs(std::int64_t{});
  } else if (valueType == openvdb::typeNameAsString<std::int16_t>()) {
    readAs(std::int16_t{});
  } else {
    throw Error("attribute '" + name + "' has unsupported type " + valueType);
  }
  return true;
}

bool readVector(const PointDataGrid& grid, const std::string& name, std::vector<glm::vec3>& values) {
  const auto leaf0 = grid.tree().cbeginLeaf();
  if (!leaf0) return false;
  const std::size_t index = leaf0->attributeSet().find(name);
  if (index == openvdb::points::AttributeSet::INVALID_POS) return false;
  const std::string valueType = leaf0->constAttributeArray(index).valueType();
  if (valueType != openvdb::typeNameAsString<openvdb::Vec3f>()) {
    throw Error("attribute '" + name + "' has type " + valueType + ", expected vec3s");
  }
  for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
    const AttributeHandle<openvdb::Vec3f> handle(leaf->constAttributeArray(index));
    for (auto point = leaf->beginIndexOn(); point; ++point) {
      const openvdb::Vec3f v = handle.get(*point);
      values.emplace_back(v.x(), v.y(), v.z());
    }
  }
  return true;
}

PointDataGrid::Ptr readPointGrid(openvdb::io::File& file, const std::string& gridName) {
  std::vector<std::string> names;
  std::vector<std::string> pointNames;
  for (auto name = file.beginName(); name != file.endName(); ++name) {
    names.push_back(*name);
    if (file.readGridMetadata(*name)->isType<PointDataGrid>()) pointNames.push_back(*name);
  }
  std::string chosen = gridName;
  if (chosen.empty()) {
    if (pointNames.empty()) throw Error("no point grid among its grids (" + joinNames(names) + ")");
    chosen = pointNames.front();
  } else if (std::find(names.begin(), names.end(), chosen) == names.end()) {
    throw Error("no grid '" + chosen + "'; its grids are " + joinNames(names));
  } else if (std::find(pointNames.begin(), pointNames.end(), chosen) == pointNames.end()) {
    throw Error("grid '" + chosen + "' is not a point grid; its point grids are " + joinNames(pointNames));
  }
  return openvdb::gridPtrCast<PointDataGrid>(file.readGrid(chosen));
}

ParticleFileData readGridPoints(const PointDataGrid& grid) {
  ParticleFileData data;
  const auto leaf0 = grid.tree().cbeginLeaf();
  if (!leaf0) return data;
  if (leaf0->attributeSet().find("P") == openvdb::points::AttributeSet::INVALID_POS) {
    throw Error("point grid '" + grid.getName() + "' has no P attribute");
  }
  // Nine floats per point at most come out (position, velocity, life, flag); checked before any is copied.
  const openvdb::Index64 count = openvdb::points::pointCount(grid.tree());
  requireMemory(count * 9 * sizeof(float),
                "point grid '" + grid.getName() + "': " + std::to_string(count) + " points");
  data.positions.reserve(count);
  const openvdb::math::Transform& transform = grid.transform();
  for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
    const AttributeHandle<openvdb::Vec3f> positions(leaf->constAttributeArray("P"));
    for (auto point = leaf->beginIndexOn(); point; ++point) {
      // P is stored relative to the voxel centre, in index units.
      const openvdb::Vec3d world = transform.indexToWorld(point.getCoord().asVec3d() + positions.get(*point));
      data.positions.emplace_back(float(world.x()), float(world.y()), float(world.z()));
    }
  }
  readScalar(grid, "U", data.typeFlags);
  readScalar(grid, "particles_life_secondary", data.life);
  readScalar(grid, "pscale", data.radii);
  for (const char* name : {"particles_velocity_secondary", "particles_velocity", "v"}) {
    if (readVector(grid, name, data.velocities)) break;
  }
  return data;
}

}  // namespace

ParticleFileData readVdbPoints(const std::filesystem::path& path, const std::string& gridName) {
  initializeOpenVdb();
  const std::string where = path.string() + ": ";
  std::error_code ignored;
  if (!std::filesystem::is_regular_file(path, ignored)) throw Error(where + "no such file");
  try {
    openvdb::io::File file(path.string());
    file.open(/*delayLoad=*/false);
    const PointDataGrid::Ptr grid = readPointGrid(file, gridName);
    file.close();
    return readGridPoints(*grid);
  } catch (const Error& error) {
    throw Error(where + error.what());
  } catch (const std::exception& error) {
    // OpenVDB reports a file that is not a VDB, a truncated file or an unregistered attribute type this way.
    throw Error(where + "cannot read OpenVDB points: " + error.what());
  }
}

}  // namespace spindrift
