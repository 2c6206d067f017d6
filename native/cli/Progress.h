#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace spindrift::cli {

/// Reports progress through a sequence of frames on stderr: a bar redrawn in place on a terminal, one plain
/// line per frame otherwise (a farm's log file), nothing when quiet.
class Progress {
 public:
  Progress(int total, bool quiet);
  void frameDone(int frame, double frameSeconds);
  /// A frame left out because its files exist (--skip-existing); it counts towards the total.
  void frameSkipped(int frame);
  void finish();

 private:
  int total_;
  int done_ = 0;
  bool quiet_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_;
};

/// Parses "12", "1-240", "1-240:2" or a comma list of those into frame numbers, in order; throws
/// std::invalid_argument with the bad part.
std::vector<int> parseFrameList(const std::string& text);

}  // namespace spindrift::cli
