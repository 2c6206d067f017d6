#include "Sequence.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <fstream>
#include <system_error>

#include "spindrift/Error.h"
#include "spindrift/Scene.h"

namespace spindrift::cli {
namespace {

std::atomic<int> receivedSignal{0};
struct sigaction previousInterrupt, previousTerminate;

extern "C" void recordStopSignal(int signalNumber) {
  receivedSignal.store(signalNumber);
  // A second signal takes the default action: the user (or the scheduler) insists.
  struct sigaction defaultAction {};
  defaultAction.sa_handler = SIG_DFL;
  sigemptyset(&defaultAction.sa_mask);
  sigaction(SIGINT, &defaultAction, nullptr);
  sigaction(SIGTERM, &defaultAction, nullptr);
}

}  // namespace

StopSignals::StopSignals() {
  receivedSignal.store(0);
  struct sigaction action {};
  action.sa_handler = recordStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // A write in progress goes on; the loop decides when to stop.
  sigaction(SIGINT, &action, &previousInterrupt);
  sigaction(SIGTERM, &action, &previousTerminate);
}

StopSignals::~StopSignals() {
  sigaction(SIGINT, &previousInterrupt, nullptr);
  sigaction(SIGTERM, &previousTerminate, nullptr);
}

int StopSignals::received() {
  return receivedSignal.load();
}

std::vector<std::filesystem::path> perFrameOutputs(const std::vector<std::string>& patterns, int frame,
                                                   bool singleFrame) {
  std::vector<std::filesystem::path> outputs;
  for (const std::string& pattern : patterns)
    if (!pattern.empty() && (singleFrame || pattern.find('#') != std::string::npos))
      outputs.push_back(pathForFrame(pattern, frame));
  return outputs;
}

bool allExist(const std::vector<std::filesystem::path>& outputs) {
  for (const std::filesystem::path& output : outputs)
    if (!std::filesystem::is_regular_file(output)) return false;
  return !outputs.empty();
}

int removeStaleTemporaries(const std::filesystem::path& target) {
  const std::filesystem::path directory = target.parent_path().empty() ? "." : target.parent_path();
  const std::string prefix = "." + target.filename().string() + ".tmp-";
  std::error_code error;
  int removed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
    const std::string name = entry.path().filename().string();
    if (name.compare(0, prefix.size(), prefix) == 0 && std::filesystem::remove(entry.path(), error))
      ++removed;
  }
  return removed;
}

void writeTextFile(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path temporary =
      path.parent_path() / ("." + path.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-text");
  {
    std::ofstream stream(temporary, std::ios::binary);
    stream << text;
    if (!stream.flush()) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw Error(path.string() + ": cannot write");
    }
  }
  std::error_code renameError;
  std::filesystem::rename(temporary, path, renameError);
  if (renameError) {
    std::filesystem::remove(temporary, renameError);
    throw Error(path.string() + ": cannot write: " + renameError.message());
  }
}

}  // namespace spindrift::cli
