#include "gl/GlThread.h"

#include "gl/EglContext.h"

namespace spindrift {

GlThread::GlThread() {
  std::promise<void> started;
  std::future<void> startResult = started.get_future();
  thread_ = std::thread([this, &started] { loop(started); });
  try {
    startResult.get();
  } catch (...) {
    thread_.join();  // The loop has already returned: the context failed.
    throw;
  }
}

GlThread::~GlThread() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
}

void GlThread::post(std::function<void()> work) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(std::move(work));
  }
  wake_.notify_one();
}

void GlThread::loop(std::promise<void>& started) {
  std::unique_ptr<EglContext> context;
  try {
    context = std::make_unique<EglContext>();
    renderer_ = context->renderer();
    version_ = context->version();
  } catch (...) {
    started.set_exception(std::current_exception());
    return;
  }
  started.set_value();
  for (;;) {
    std::function<void()> work;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) break;  // Stopping, and every queued task has run.
      work = std::move(queue_.front());
      queue_.pop_front();
    }
    work();  // A packaged_task: exceptions travel to the caller's future.
  }
}

}  // namespace spindrift
