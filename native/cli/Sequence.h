#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace spindrift::cli {

/// The exit codes of `spindrift` (docs/reliability.md lists them for farm schedulers).
enum ExitCode : int {
  kExitSuccess = 0,  ///< Every frame was written (or skipped because it existed).
  kExitError = 1,  ///< A scene, file or rendering error; in a sequence, a frame failed without --keep-going.
  kExitUsage = 2,  ///< Bad command line.
  kExitFramesFailed = 3,  ///< --keep-going: the sequence ran to its end, but at least one frame failed.
  // 128 + signal number (130 SIGINT, 143 SIGTERM): stopped by a signal; every file written is complete.
};

/// SIGINT and SIGTERM only set a flag; the frame loop reads it between frames and before writing, so a
/// frame's files are either all written or none is, and no temporary file is left behind. A second signal
/// of either kind terminates at once (the default action), for a user who does not want to wait for the
/// frame in flight; a later run cleans the temporary it may leave (see removeStaleTemporaries).
class StopSignals {
 public:
  StopSignals();   ///< Installs the handlers.
  ~StopSignals();  ///< Restores the previous ones.
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  /// The signal received (SIGINT or SIGTERM), or 0.
  static int received();
};

/// Every file that rendering `frame` writes: the non-empty output patterns with #### replaced. In a sequence
/// (`singleFrame` false) names without #### (the combined stats file) are left out, as they are not per
/// frame.
std::vector<std::filesystem::path> perFrameOutputs(const std::vector<std::string>& patterns, int frame,
                                                   bool singleFrame);

/// True when every file in `outputs` exists (a partial frame, say an EXR without its PNG, is not done).
/// Files are only ever renamed into place complete, so existence means complete.
bool allExist(const std::vector<std::filesystem::path>& outputs);

/// Removes temporaries (".<name>.tmp-<pid>-<n>") that a process killed while writing `target` left beside
/// it. Only the task rendering a frame writes its files, so any such temporary is stale. Returns how many.
int removeStaleTemporaries(const std::filesystem::path& target);

/// Writes text to `path` through a temporary name and a rename, like the image writers.
void writeTextFile(const std::filesystem::path& path, const std::string& text);

}  // namespace spindrift::cli
