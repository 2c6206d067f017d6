// libFuzzer harness: OpenVDB point loading (grid choice, attribute lookup and types, Mantaflow flags,
// transforms). The input is not a VDB file: it describes one (FuzzedDataProvider), which this harness builds
// with OpenVDB and writes, so every run reaches Spindrift's reader instead of stopping in OpenVDB's
// deserialiser (which is not hardened against hostile files, and not ours to fix).
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdint>

#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/points/PointDataGrid.h>

#include "FuzzInput.h"
#include "io/ParticleFile.h"
#include "spindrift/Error.h"
#include "spindrift/Limits.h"

namespace {

using namespace openvdb;
using namespace openvdb::points;

const char* const kNames[] = {
    "P",      "U", "particles_velocity", "particles_velocity_secondary", "v", "particles_life_secondary",
    "pscale", "x"};
const char* const kGridNames[] = {"particles", "particles_secondary", "", "velocity"};

float anyFloat(FuzzedDataProvider& input) {
  switch (input.ConsumeIntegralInRange<int>(0, 7)) {
    case 0:
      return std::nanf("");
    case 1:
      return INFINITY;
    case 2:
      return -1e30f;
    case 3:
      return 3e9f;  // Beyond int32: a flag read from a float attribute must not overflow.
    default:
      return input.ConsumeFloatingPointInRange<float>(-100.0f, 100.0f);
  }
}

template <typename Value>
void addAttribute(PointDataGrid& grid, const std::string& name, FuzzedDataProvider& input, bool truncate) {
  NamePair type = TypedAttributeArray<Value>::attributeType();
  // Mantaflow's half-precision storage exists for the types it writes.
  if constexpr (std::is_same_v<Value, float> || std::is_same_v<Value, Vec3f> ||
                std::is_same_v<Value, std::int32_t>)
    if (truncate) type = TypedAttributeArray<Value, TruncateCodec>::attributeType();
  appendAttribute(grid.tree(), name, type);
  for (auto leaf = grid.tree().beginLeaf(); leaf; ++leaf) {
    AttributeWriteHandle<Value> handle(leaf->attributeArray(name));
    for (auto index = leaf->beginIndexOn(); index; ++index) {
      if constexpr (std::is_same_v<Value, Vec3f>)
        handle.set(*index, Vec3f(anyFloat(input), anyFloat(input), anyFloat(input)));
      else if constexpr (std::is_floating_point_v<Value>)
        handle.set(*index, Value(anyFloat(input)));
      else
        handle.set(*index, input.ConsumeIntegral<Value>());
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  openvdb::initialize();
  if (!TypedAttributeArray<std::int32_t, TruncateCodec>::isRegistered())
    TypedAttributeArray<std::int32_t, TruncateCodec>::registerType();
  if (!TypedAttributeArray<float, TruncateCodec>::isRegistered())
    TypedAttributeArray<float, TruncateCodec>::registerType();
  if (!TypedAttributeArray<Vec3f, TruncateCodec>::isRegistered())
    TypedAttributeArray<Vec3f, TruncateCodec>::registerType();
  spindrift::setMemoryLimitBytes(std::uint64_t(512) << 20);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider input(data, size);
  // The points are placed with a sane transform; the fuzzed one (any voxel size, translation, even NaN or
  // infinite) replaces it afterwards, so only the reader meets it.
  std::vector<Vec3f> positions(input.ConsumeIntegralInRange<std::size_t>(0, 48));
  for (Vec3f& p : positions)
    p = Vec3f(input.ConsumeFloatingPointInRange<float>(-50.0f, 50.0f),
              input.ConsumeFloatingPointInRange<float>(-50.0f, 50.0f),
              input.ConsumeFloatingPointInRange<float>(-50.0f, 50.0f));
  PointDataGrid::Ptr grid;
  const bool withPositions = input.ConsumeBool() || positions.empty();
  if (withPositions) {
    grid = createPointDataGrid<NullCodec, PointDataGrid>(positions,
                                                         *math::Transform::createLinearTransform(0.1));
  } else {
    grid = PointDataGrid::create();  // An empty tree: a frame where Mantaflow wrote no particles.
  }
  const double voxelSize = input.ConsumeBool() ? input.ConsumeFloatingPointInRange<double>(1e-6, 1e6) : 0.1;
  math::Transform::Ptr transform;
  try {
    transform = math::Transform::createLinearTransform(voxelSize);
    transform->postTranslate(Vec3d(anyFloat(input), anyFloat(input), anyFloat(input)));
    if (input.ConsumeBool()) transform->postScale(Vec3d(anyFloat(input), anyFloat(input), anyFloat(input)));
  } catch (const std::exception&) {
    return 0;  // OpenVDB refuses the transform (a zero scale): no file to read.
  }
  grid->setTransform(transform);
  grid->setName(kGridNames[input.ConsumeIntegralInRange<int>(0, 3)]);

  const int attributeCount = input.ConsumeIntegralInRange<int>(0, 5);
  for (int i = 0; i < attributeCount && grid->tree().cbeginLeaf(); ++i) {
    const std::string name = kNames[input.ConsumeIntegralInRange<int>(1, 7)];
    if (grid->tree().cbeginLeaf()->attributeSet().find(name) != AttributeSet::INVALID_POS) continue;
    const bool truncate = input.ConsumeBool();
    switch (input.ConsumeIntegralInRange<int>(0, 5)) {
      case 0:
        addAttribute<std::int32_t>(*grid, name, input, truncate);
        break;
      case 1:
        addAttribute<float>(*grid, name, input, truncate);
        break;
      case 2:
        addAttribute<Vec3f>(*grid, name, input, truncate);
        break;
      case 3:
        addAttribute<double>(*grid, name, input, false);
        break;
      case 4:
        addAttribute<std::int64_t>(*grid, name, input, false);
        break;
      default:
        addAttribute<std::int16_t>(*grid, name, input, false);
        break;
    }
  }
  GridPtrVec grids;
  if (input.ConsumeBool()) {
    FloatGrid::Ptr other = FloatGrid::create();
    other->setName("density");
    grids.push_back(other);
  }
  grids.push_back(grid);
  const std::string requested =
      input.ConsumeBool() ? "" : kGridNames[input.ConsumeIntegralInRange<int>(0, 3)];

  const std::filesystem::path path = fuzz::scratchDirectory() / "input.vdb";
  try {
    io::File(path.string()).write(grids);
  } catch (const std::exception&) {
    return 0;  // OpenVDB cannot write this transform (a singular or NaN matrix): no file to read.
  }
  try {
    const spindrift::ParticleFileData particles = spindrift::readVdbPoints(path, requested);
    FUZZ_REQUIRE(particles.positions.size() == positions.size() || !withPositions);
    fuzz::checkParticleArrays(particles);
  } catch (const spindrift::Error&) {
  }
  return 0;
}
