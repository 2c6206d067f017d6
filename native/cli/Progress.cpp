#include "Progress.h"

#include <unistd.h>

#include <sstream>
#include <stdexcept>

namespace spindrift::cli {

Progress::Progress(int total, bool quiet)
    : total_(total),
      quiet_(quiet),
      terminal_(isatty(fileno(stderr))),
      start_(std::chrono::steady_clock::now()) {}

void Progress::frameDone(int frame, double frameSeconds) {
  ++done_;
  if (quiet_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double remaining = elapsed / done_ * (total_ - done_);
  if (!terminal_) {
    std::fprintf(stderr, "frame %d done in %.2f s (%d/%d, %.0f s left)\n", frame, frameSeconds, done_, total_,
                 remaining);
    return;
  }
  constexpr int kBarWidth = 30;
  const int filled = total_ > 0 ? done_ * kBarWidth / total_ : kBarWidth;
  std::string bar(std::size_t(filled), '#');
  bar.resize(kBarWidth, '-');
  std::fprintf(stderr, "\r[%s] %d/%d  frame %d  %.2f s/frame  %.0f s left   ", bar.c_str(), done_, total_,
               frame, elapsed / done_, remaining);
  std::fflush(stderr);
}

void Progress::frameSkipped(int frame) {
  --total_;  // The estimate of the time left counts frames that will be rendered.
  if (!quiet_) std::fprintf(stderr, "%sframe %d skipped: its files exist\n", terminal_ ? "\r" : "", frame);
}

void Progress::finish() {
  if (!quiet_ && terminal_ && done_ > 0) std::fprintf(stderr, "\n");
}

std::vector<int> parseFrameList(const std::string& text) {
  std::vector<int> frames;
  std::stringstream parts(text);
  for (std::string part; std::getline(parts, part, ',');) {
    int first = 0, last = 0, step = 1;
    char dash = 0, colon = 0;
    std::istringstream in(part);
    if (!(in >> first)) throw std::invalid_argument("bad frame \"" + part + "\"");
    last = first;
    if (in >> dash) {
      if (dash != '-' || !(in >> last)) throw std::invalid_argument("bad frame range \"" + part + "\"");
      if (in >> colon && (colon != ':' || !(in >> step) || step <= 0))
        throw std::invalid_argument("bad frame step in \"" + part + "\"");
    }
    std::string rest;
    if (in >> rest) throw std::invalid_argument("bad frame range \"" + part + "\"");
    if (last < first) throw std::invalid_argument("frame range \"" + part + "\" runs backwards");
    if ((long long)(last - first) / step > 1000000)
      throw std::invalid_argument("frame range \"" + part + "\" is too long");
    for (int frame = first; frame <= last; frame += step)
      frames.push_back(frame);
  }
  if (frames.empty()) throw std::invalid_argument("no frames in \"" + text + "\"");
  return frames;
}

}  // namespace spindrift::cli
