// WorkerThreadLimit (spindrift render --threads): the preparation's TBB loops use at most the threads it
// allows while it lives, and all of them again afterwards.
#include <gtest/gtest.h>

#include <mutex>
#include <set>
#include <thread>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "spindrift/Error.h"
#include "spindrift/Threads.h"

namespace {

std::size_t allowedParallelism() {
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
}

// The distinct threads a parallel loop with enough work for several runs on.
std::size_t threadsOfAParallelLoop() {
  std::set<std::thread::id> threads;
  std::mutex mutex;
  tbb::parallel_for(0, 1 << 16, [&](int) {
    volatile double sum = 0.0;
    for (int k = 0; k < 200; ++k)
      sum = sum + k;
    const std::lock_guard<std::mutex> lock(mutex);
    threads.insert(std::this_thread::get_id());
  });
  return threads.size();
}

}  // namespace

TEST(WorkerThreadLimit, OneThreadRunsTheParallelLoopsAloneWhileTheLimitLives) {
  const std::size_t before = allowedParallelism();
  {
    const spindrift::WorkerThreadLimit limit(1);
    EXPECT_EQ(allowedParallelism(), 1u);
    EXPECT_EQ(threadsOfAParallelLoop(), 1u);
  }
  EXPECT_EQ(allowedParallelism(), before);
}

TEST(WorkerThreadLimit, ZeroThreadsIsRefused) {
  EXPECT_THROW(spindrift::WorkerThreadLimit(0), spindrift::Error);
}
