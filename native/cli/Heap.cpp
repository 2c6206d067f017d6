#include "Heap.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "spindrift/Limits.h"

namespace spindrift::cli {
namespace {

// glibc's largest mmap threshold: blocks up to this size come from the heap. The population is made of
// blocks of half of it, so that each is one run of the heap that a target of up to that size can reuse.
constexpr int kMmapThreshold = 32 << 20;
constexpr std::size_t kBlockBytes = std::size_t(kMmapThreshold) / 2;
// Freed memory stays in the heap up to this much at its top (mallopt takes an int); the population stays
// below it, or freeing it would hand it back to the kernel.
constexpr int kTrimThreshold = 1 << 30;
constexpr std::uint64_t kMostPopulated = std::uint64_t(kTrimThreshold) - (std::uint64_t(64) << 20);
constexpr std::size_t kPageBytes = 4096;
constexpr std::uintptr_t kHugePageBytes = std::uintptr_t(2) << 20;
// glibc's default M_TOP_PAD, restored once the population's heap is taken.
constexpr int kDefaultTopPad = 128 << 10;

}  // namespace

// A frame allocates the same large buffers as the last (the preparation's arrays, the readback, the EXR's
// lines). glibc hands blocks over 128 KiB back to the kernel when they are freed and takes them again with
// page faults at the next frame: 9 % of a dam-break sequence's time on the benchmark machine, where keeping
// them took the frame from 705-724 to 653-671 ms. One arena: with one per thread, the GL thread's heap (the
// driver's textures) grew apart from the populated one, and the first frame faulted its 13,000 pages in as
// before (docs/frame-cost.md, session 46).
void keepTheHeap() {
  mallopt(M_MMAP_THRESHOLD, kMmapThreshold);
  mallopt(M_TRIM_THRESHOLD, kTrimThreshold);
  mallopt(M_ARENA_MAX, 1);
}

std::uint64_t firstFrameHeapBytes(int width, int height) {
  if (width <= 0 || height <= 0) return 0;
  return (std::uint64_t(128) << 20) + std::uint64_t(700) * std::uint64_t(width) * std::uint64_t(height);
}

// Under AddressSanitizer malloc is the sanitizer's allocator, which neither mallopt nor freed blocks steer.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kGlibcAllocator = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kGlibcAllocator = false;
#else
constexpr bool kGlibcAllocator = true;
#endif
#else
constexpr bool kGlibcAllocator = true;
#endif

HeapPopulation::HeapPopulation(std::uint64_t bytes) {
  if (!kGlibcAllocator) {
    notPopulated_ = "built with AddressSanitizer, whose allocator is not glibc's";
    return;
  }
  const std::uint64_t allowed = std::min({bytes, availableMemoryBytes() / 2, kMostPopulated});
  if (allowed < bytes)
    notPopulated_ = "capped at " + std::to_string(allowed >> 20) + " MiB (half the memory available, " +
                    std::to_string(kMostPopulated >> 20) + " MiB at most)";
  if (allowed == 0) return;
  thread_ = std::thread([this, allowed] { populate(allowed); });
}

HeapPopulation::~HeapPopulation() {
  wait();
}

void HeapPopulation::wait() {
  if (thread_.joinable()) thread_.join();
}

// The heap's pages as 2 MiB pages where the kernel has them (transparent huge pages, which a kernel set to
// "madvise" gives only where asked). The heap grows by all of `bytes` at once, before any block is carved
// from it, so that no 4 KiB page is written into the range before it is marked. On the benchmark's machine a
// one-frame dam break's frame took 325-340 ms instead of 508-550 (docs/frame-cost.md, session 47).
static void askForHugePages(std::uint64_t bytes) {
  const auto begin = reinterpret_cast<std::uintptr_t>(sbrk(0));
  mallopt(M_TOP_PAD, int(std::min<std::uint64_t>(bytes, std::uint64_t(kTrimThreshold))));
  // A block no free one can serve comes from the heap's top, which grows by it and the pad; freed, it joins
  // the top again, which stays (the trim threshold is above the population). Volatile: a compiler may drop
  // an unused malloc and its free.
  void* volatile probe = std::malloc(kBlockBytes);
  mallopt(M_TOP_PAD, kDefaultTopPad);
  std::free(probe);
  const auto end = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const auto first = (begin + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const auto last = end & ~(kHugePageBytes - 1);
  if (last <= first) return;
#ifdef MADV_HUGEPAGE
  madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#endif
}

std::string transparentHugePagesMode() {
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!std::getline(file, line)) return "unknown";
  const auto open = line.find('['), close = line.find(']');
  return open != std::string::npos && close > open ? line.substr(open + 1, close - open - 1) : "unknown";
}

// The process's anonymous memory the kernel maps with huge pages, from /proc/self/smaps_rollup.
static std::uint64_t anonymousHugePageBytes() {
  std::ifstream file("/proc/self/smaps_rollup");
  std::string line;
  while (std::getline(file, line)) {
    std::istringstream fields(line);
    std::string key;
    std::uint64_t kib = 0;
    if (fields >> key >> kib && key == "AnonHugePages:") return kib << 10;
  }
  return 0;
}

void HeapPopulation::populate(std::uint64_t bytes) {
  const auto start = std::chrono::steady_clock::now();
  askForHugePages(bytes);
  std::vector<void*> blocks;
  for (std::uint64_t taken = 0; taken < bytes; taken += kBlockBytes) {
    const std::size_t blockBytes = std::size_t(std::min<std::uint64_t>(kBlockBytes, bytes - taken));
    void* block = std::malloc(blockBytes);
    if (!block) break;
    blocks.push_back(block);
    const auto first = (reinterpret_cast<std::uintptr_t>(block) + kPageBytes - 1) & ~(kPageBytes - 1);
    const auto last = (reinterpret_cast<std::uintptr_t>(block) + blockBytes) & ~(kPageBytes - 1);
    if (last <= first) continue;
#ifdef MADV_POPULATE_WRITE
    if (madvise(reinterpret_cast<void*>(first), last - first, MADV_POPULATE_WRITE) != 0) {
      notPopulated_ = std::string("madvise(MADV_POPULATE_WRITE): ") + std::strerror(errno) +
                      (errno == EINVAL ? " (it needs Linux 5.14)" : "");
      break;
    }
    populated_ += last - first;
#else
    (void)first;
    (void)last;
    notPopulated_ = "built without MADV_POPULATE_WRITE";
    break;
#endif
  }
  hugePageBytes_ = anonymousHugePageBytes();
  // Freed together, the blocks join into runs that the first frame's allocations take pages from.
  for (void* block : blocks)
    std::free(block);
  milliseconds_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace spindrift::cli
