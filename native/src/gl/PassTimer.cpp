#include "gl/PassTimer.h"

namespace spindrift {

void PassTimer::begin(const std::string& passName) {
  if (queries_.size() <= frame_.size()) queries_.push_back(createTimeElapsedQuery());
  frame_.push_back({passName, 0.0, 0.0});
  glBeginQuery(GL_TIME_ELAPSED, queries_[frame_.size() - 1].id());
  started_ = std::chrono::steady_clock::now();
}

void PassTimer::end() {
  glEndQuery(GL_TIME_ELAPSED);
  frame_.back().cpuMilliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started_).count();
}

std::vector<PassTiming> PassTimer::collect() {
  for (std::size_t i = 0; i < frame_.size(); ++i) {
    GLuint64 nanoseconds = 0;
    glGetQueryObjectui64v(queries_[i].id(), GL_QUERY_RESULT, &nanoseconds);
    frame_[i].gpuMilliseconds = double(nanoseconds) * 1e-6;
  }
  std::vector<PassTiming> timings;
  timings.swap(frame_);
  return timings;
}

}  // namespace spindrift
