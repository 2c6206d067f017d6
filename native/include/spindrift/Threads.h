#pragma once

#include <memory>

namespace spindrift {

/// Caps the worker threads of the CPU preparation (TBB) while it lives; `threads` >= 1. A farm task gives
/// it the CPUs the scheduler granted (`spindrift render --threads $SLURM_CPUS_PER_TASK`). Images do not
/// depend on it: the preparation's parallel loops write disjoint, order-preserving blocks (tested).
class WorkerThreadLimit {
 public:
  explicit WorkerThreadLimit(int threads);
  ~WorkerThreadLimit();
  WorkerThreadLimit(const WorkerThreadLimit&) = delete;
  WorkerThreadLimit& operator=(const WorkerThreadLimit&) = delete;

 private:
  struct Control;
  std::unique_ptr<Control> control_;
};

}  // namespace spindrift
