#pragma once

#include <cstdint>
#include <string>
#include <thread>

// The CLI's process is ours, so it shapes glibc's heap for the way a render uses memory (docs/frame-cost.md,
// "The first frame's heap mapped at once"). The Python module leaves Blender's heap alone.
namespace spindrift::cli {

/// Set before any thread starts: blocks up to 32 MiB come from the heap and freed ones stay in it (a frame
/// allocates the same large buffers as the last), and every thread allocates from the one heap, the GL
/// driver's textures included, so that the pages populated below serve them all.
void keepTheHeap();

/// The heap a process's first frame of width × height takes, from the benchmark's frames: about 700 bytes a
/// pixel (the GL driver's targets, the readback, the EXR's lines) and 128 MiB besides (the driver's programs,
/// the particles and their preparation; 64 MiB left the drop example 17,900 faults). 480×270: 215 MiB;
/// 960×540: 474 MiB.
std::uint64_t firstFrameHeapBytes(int width, int height);

/// The kernel's transparent huge pages setting: "always", "madvise" (where a process asks), "never" or
/// "unknown".
std::string transparentHugePagesMode();

/// Maps `bytes` of fresh heap at once (MADV_POPULATE_WRITE) on a thread of its own, and frees them into the
/// heap, where the first frame's blocks find them: a page the kernel maps this way costs a fraction of one
/// faulted in at its first write (0.67 against 11.8 µs on the benchmark's VM). The range asks for transparent
/// huge pages first (MADV_HUGEPAGE), which took the first frame's passes, preparation and readback a third
/// faster on that VM. Half the memory available at most; nothing where the kernel cannot (before Linux
/// 5.14), under AddressSanitizer or when `bytes` is 0.
class HeapPopulation {
 public:
  explicit HeapPopulation(std::uint64_t bytes);
  ~HeapPopulation();
  HeapPopulation(const HeapPopulation&) = delete;
  HeapPopulation& operator=(const HeapPopulation&) = delete;

  /// Waits for the thread; then the stats below are final.
  void wait();
  std::uint64_t populatedBytes() const { return populated_; }
  /// Why fewer bytes than asked were populated; empty when all were.
  const std::string& notPopulated() const { return notPopulated_; }
  double milliseconds() const { return milliseconds_; }
  /// How much of the process's memory the kernel mapped with huge pages once the heap was populated.
  std::uint64_t hugePageBytes() const { return hugePageBytes_; }

 private:
  void populate(std::uint64_t bytes);

  std::thread thread_;
  std::uint64_t populated_ = 0;
  std::string notPopulated_;
  double milliseconds_ = 0.0;
  std::uint64_t hugePageBytes_ = 0;
};

}  // namespace spindrift::cli
