#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "gl/GlObjects.h"
#include "spindrift/RenderResult.h"

namespace spindrift {

/// Times each pass of a frame with GL timestamp queries (GPU time) and a steady clock (the CPU time spent
/// issuing it), and counts the samples its draws wrote (GL_SAMPLES_PASSED).
/// Queries are pooled and reused, so timing allocates no GL objects after the first frames.
class PassTimer {
 public:
  /// Starts timing a pass; the matching `end` must follow before the next `begin` (passes do not nest).
  void begin(const std::string& passName);
  void end();
  /// Waits for the frame's queries and returns one timing per pass, in order; clears the frame.
  std::vector<PassTiming> collect();

 private:
  std::vector<QueryObject> queries_;
  std::vector<QueryObject> sampleQueries_;  // one per pass
  std::vector<PassTiming> frame_;
  std::chrono::steady_clock::time_point started_;
};

/// Times the scope it lives in as one pass.
class ScopedPassTimer {
 public:
  ScopedPassTimer(PassTimer& timer, const std::string& passName) : timer_(timer) { timer_.begin(passName); }
  ~ScopedPassTimer() { timer_.end(); }
  ScopedPassTimer(const ScopedPassTimer&) = delete;
  ScopedPassTimer& operator=(const ScopedPassTimer&) = delete;

 private:
  PassTimer& timer_;
};

/// Runs `issuePass` timed as the pass `passName` and returns what it returns.
template <class IssuePass>
auto timePass(PassTimer& timer, const std::string& passName, IssuePass&& issuePass) -> decltype(issuePass()) {
  ScopedPassTimer timed(timer, passName);
  return issuePass();
}

}  // namespace spindrift
