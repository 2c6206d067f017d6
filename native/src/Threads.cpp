#include "spindrift/Threads.h"

#include <string>

#include <tbb/global_control.h>

#include "spindrift/Error.h"

namespace spindrift {

// The global_control is built in place: a copy of one (what aggregate-initialising this struct from a
// temporary and handing it to make_unique made) holds no limit, and the temporary's destructor lifts the
// limit the moment it is set, so until 2026-12-03 `--threads` limited nothing.
struct WorkerThreadLimit::Control {
  explicit Control(std::size_t threads) : control(tbb::global_control::max_allowed_parallelism, threads) {}
  tbb::global_control control;
};

WorkerThreadLimit::WorkerThreadLimit(int threads) {
  if (threads < 1) throw Error("threads: " + std::to_string(threads) + " must be at least 1");
  control_ = std::make_unique<Control>(std::size_t(threads));
}

WorkerThreadLimit::~WorkerThreadLimit() = default;

}  // namespace spindrift
