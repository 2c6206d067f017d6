#pragma once

// What the CPU offers the preparation's vectorised loops (prep/NeighbourOffsets.cpp, prep/OcclusionRows.cpp),
// asked once per process.
namespace spindrift {

inline bool cpuHasAvx512() {
  static const bool has = [] {
    __builtin_cpu_init();  // harmless if libgcc's constructor has run; needed if it has not
    return __builtin_cpu_supports("avx512f") != 0;
  }();
  return has;
}

}  // namespace spindrift
