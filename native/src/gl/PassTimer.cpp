#include "gl/PassTimer.h"

#include <cstdlib>

namespace spindrift {
namespace {

// SPINDRIFT_FINISH_PASSES=1 finishes the GL's work at each pass's start and end. A driver may defer a pass's
// work until something reads its result (llvmpipe rasterises a framebuffer's draws when a later pass samples
// it), which then counts in the later pass's time; finishing puts each cost where it is issued, at the
// price of the overlap. For profiling only: the benchmark's frame times are taken without it.
bool finishPasses() {
  static const bool finish = [] {
    const char* value = std::getenv("SPINDRIFT_FINISH_PASSES");
    return value && *value && std::string(value) != "0";
  }();
  return finish;
}

}  // namespace

// Each pass is bracketed by two GL_TIMESTAMP queries rather than one GL_TIME_ELAPSED query: Mesa's llvmpipe
// reports a nonsensical elapsed time for the first query of a context, while its timestamps are sound.
void PassTimer::begin(const std::string& passName) {
  while (queries_.size() < 2 * (frame_.size() + 1))
    queries_.push_back(createQuery(GL_TIMESTAMP));
  if (finishPasses()) glFinish();
  frame_.push_back({passName, 0.0, 0.0});
  glQueryCounter(queries_[2 * (frame_.size() - 1)].id(), GL_TIMESTAMP);
  while (sampleQueries_.size() < frame_.size())
    sampleQueries_.push_back(createQuery(GL_SAMPLES_PASSED));
  glBeginQuery(GL_SAMPLES_PASSED, sampleQueries_[frame_.size() - 1].id());
  started_ = std::chrono::steady_clock::now();
}

void PassTimer::end() {
  if (finishPasses()) glFinish();
  glEndQuery(GL_SAMPLES_PASSED);
  glQueryCounter(queries_[2 * (frame_.size() - 1) + 1].id(), GL_TIMESTAMP);
  frame_.back().cpuMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started_).count();
}

std::vector<PassTiming> PassTimer::collect() {
  for (std::size_t i = 0; i < frame_.size(); ++i) {
    GLuint64 startNanoseconds = 0, endNanoseconds = 0;
    glGetQueryObjectui64v(queries_[2 * i].id(), GL_QUERY_RESULT, &startNanoseconds);
    glGetQueryObjectui64v(queries_[2 * i + 1].id(), GL_QUERY_RESULT, &endNanoseconds);
    frame_[i].gpuMilliseconds =
        endNanoseconds > startNanoseconds ? double(endNanoseconds - startNanoseconds) * 1e-6 : 0.0;
    GLuint64 samples = 0;
    glGetQueryObjectui64v(sampleQueries_[i].id(), GL_QUERY_RESULT, &samples);
    frame_[i].samplesPassed = samples;
  }
  std::vector<PassTiming> timings;
  timings.swap(frame_);
  return timings;
}

}  // namespace spindrift
