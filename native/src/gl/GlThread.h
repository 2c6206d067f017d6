#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace spindrift {

class EglContext;

/// A thread that owns an EGL context and runs GL work handed to it. All GL objects of a Renderer are made,
/// used and destroyed on this thread, so a host's own GL context (Blender's UI thread) is never disturbed and
/// GL calls never need the caller's thread to have a context.
class GlThread {
 public:
  /// Starts the thread and makes the context; rethrows the context's Error here if that fails.
  GlThread();
  /// Finishes queued work, destroys the context and joins.
  ~GlThread();
  GlThread(const GlThread&) = delete;
  GlThread& operator=(const GlThread&) = delete;

  /// Queues `work` on the GL thread and returns at once; the future carries its result or exception. Work
  /// runs in the order it was queued.
  template <typename Work>
  auto submit(Work&& work) -> std::future<decltype(work())> {
    using Result = decltype(work());
    auto task = std::make_shared<std::packaged_task<Result()>>(std::forward<Work>(work));
    std::future<Result> result = task->get_future();
    post([task] { (*task)(); });
    return result;
  }

  /// Runs `work` on the GL thread and waits for it; its result or exception comes back to the caller.
  template <typename Work>
  auto run(Work&& work) -> decltype(work()) {
    return submit(std::forward<Work>(work)).get();
  }

  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }

 private:
  void post(std::function<void()> work);
  void loop(std::promise<void>& started);

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> queue_;
  bool stopping_ = false;
  std::string renderer_;
  std::string version_;
  std::thread thread_;
};

}  // namespace spindrift
