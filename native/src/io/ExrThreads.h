#pragma once

#include <algorithm>
#include <thread>

#include <OpenEXR/ImfThreading.h>

namespace spindrift {

/// OpenEXR compresses and decompresses on its global thread pool, which is empty unless the host filled it
/// (Blender does, to its thread count): fill it only when nobody has, with one thread a core.
inline void useEveryCoreForOpenExrUnlessTheHostChose() {
  if (Imf::globalThreadCount() == 0)
    Imf::setGlobalThreadCount(int(std::max(1u, std::thread::hardware_concurrency())));
}

}  // namespace spindrift
