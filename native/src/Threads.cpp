#include "spindrift/Threads.h"

#include <string>

#include <tbb/global_control.h>

#include "spindrift/Error.h"

namespace spindrift {

struct WorkerThreadLimit::Control {
  tbb::global_control control;
};

WorkerThreadLimit::WorkerThreadLimit(int threads) {
  if (threads < 1) throw Error("threads: " + std::to_string(threads) + " must be at least 1");
  control_ = std::make_unique<Control>(
      Control{tbb::global_control(tbb::global_control::max_allowed_parallelism, std::size_t(threads))});
}

WorkerThreadLimit::~WorkerThreadLimit() = default;

}  // namespace spindrift
