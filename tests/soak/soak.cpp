// `spindrift_soak`: renders many frames in one process, as a farm node does overnight, varying particle
// counts and resolutions, writing every frame's EXR, and samples host memory (RSS), live GL objects and open
// file descriptors. After a warm-up (two passes through every size) they must stay flat. docs/reliability.md
// has a 2,000-frame run; CTest runs a short one.
//   spindrift_soak [--frames N] [--csv FILE]     exit 0 when flat, 1 when something grew
#include <dirent.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "gl/GlObjects.h"
#include "spindrift/Output.h"
#include "spindrift/Renderer.h"

namespace {

using namespace spindrift;

// Particle counts and image sizes the frames cycle through (coprime cycle lengths, so every pairing occurs).
// Small, so that 2,000 frames fit in minutes on two cores with llvmpipe: a soak looks for growth, not speed.
constexpr std::array<int, 7> kParticleCounts = {0, 100, 2000, 9000, 500, 4000, 15000};
constexpr std::array<std::array<int, 2>, 5> kSizes = {{{48, 36}, {96, 54}, {64, 64}, {128, 72}, {37, 81}}};
constexpr int kWarmUpFrames = 2 * 7 * 5;

long residentKibibytes() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

int openFileDescriptors() {
  int count = 0;
  if (DIR* directory = opendir("/proc/self/fd")) {
    while (const dirent* entry = readdir(directory))
      count += entry->d_name[0] != '.';
    closedir(directory);
  }
  return count - 1;  // The directory stream itself.
}

long liveGlObjects() {
  long total = 0;
  for (int type = 0; type < int(GlObjectType::Count); ++type)
    total += liveGlObjectCount(GlObjectType(type));
  return total;
}

// A liquid column and spray with the given number of particles, moving with the frame.
Particles particlesFor(int count, int frame) {
  std::mt19937 random{unsigned(frame)};
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  Particles particles;
  particles.reserve(std::size_t(count));
  for (int i = 0; i < count; ++i) {
    const glm::vec3 p(unit(random) * 0.8f, unit(random) * 0.8f,
                      (unit(random) + 1.0f) * 0.4f + 0.01f * (frame % 10));
    const bool spray = i % 10 == 0;
    particles.append(p, spray ? 0.01f : 0.035f, spray ? ParticleKind::Spray : ParticleKind::Liquid, 3.0f,
                     glm::vec3(0.0f, 0.0f, -1.0f));
  }
  return particles;
}

struct Sample {
  int frame;
  double seconds;
  long rssKibibytes;
  long glObjects;
  int fileDescriptors;
};

}  // namespace

int main(int argc, char** argv) {
  int frames = 2000;
  std::string csvPath;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
      frames = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc)
      csvPath = argv[++i];
    else {
      std::fprintf(stderr, "usage: spindrift_soak [--frames N] [--csv FILE]\n");
      return 2;
    }
  }
  if (frames <= kWarmUpFrames) {
    std::fprintf(stderr, "spindrift_soak: --frames must exceed the %d warm-up frames\n", kWarmUpFrames);
    return 2;
  }
  char directoryTemplate[] = "/tmp/spindrift-soak-XXXXXX";
  const std::string directory = mkdtemp(directoryTemplate);
  const std::string exrPath = directory + "/frame.exr";

  Scene scene;
  scene.camera = Camera::lookAt(64, 48, 40.0f, {0.0f, -3.5f, 1.5f}, {0.0f, 0.0f, 0.3f}, {0.0f, 0.0f, 1.0f});
  scene.background.color = {0.2f, 0.25f, 0.3f};
  Renderer renderer;
  std::vector<Sample> samples;
  std::ofstream csv;  // Written as the run goes, so a run stopped early still leaves its figures.
  if (!csvPath.empty()) {
    csv.open(csvPath);
    csv << "frame,seconds,rss_kib,gl_objects,open_fds\n";
  }
  const auto start = std::chrono::steady_clock::now();
  for (int frame = 1; frame <= frames; ++frame) {
    const auto [width, height] = kSizes[std::size_t(frame) % kSizes.size()];
    const Camera& pose = scene.camera;
    scene.camera =
        Camera::lookAt(width, height, pose.fovYDegrees, pose.position(), {0.0f, 0.0f, 0.3f}, {0, 0, 1});
    const Particles particles =
        particlesFor(kParticleCounts[std::size_t(frame) % kParticleCounts.size()], frame);
    writeExr(renderer.renderParticles(scene, particles, frame), exrPath);
    if (frame % 10 == 0 || frame == frames) {
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      samples.push_back({frame, seconds, residentKibibytes(), liveGlObjects(), openFileDescriptors()});
      const Sample& s = samples.back();
      if (csv.is_open())
        csv << s.frame << "," << s.seconds << "," << s.rssKibibytes << "," << s.glObjects << ","
            << s.fileDescriptors << std::endl;
    }
  }
  std::remove(exrPath.c_str());
  rmdir(directory.c_str());

  // Flat: after the warm-up, the last quarter's peaks do not exceed the first post-warm-up quarter's peaks
  // (RSS by more than 8 MiB of allocator noise; GL objects and descriptors not at all).
  std::vector<Sample> after;
  for (const Sample& s : samples)
    if (s.frame > kWarmUpFrames) after.push_back(s);
  const std::size_t quarter = std::max<std::size_t>(1, after.size() / 4);
  auto peak = [&](std::size_t begin, std::size_t end, auto field) {
    long value = 0;
    for (std::size_t i = begin; i < end; ++i)
      value = std::max(value, long(field(after[i])));
    return value;
  };
  const auto rss = [](const Sample& s) { return s.rssKibibytes; };
  const auto gl = [](const Sample& s) { return s.glObjects; };
  const auto fds = [](const Sample& s) { return long(s.fileDescriptors); };
  const long rssEarly = peak(0, quarter, rss), rssLate = peak(after.size() - quarter, after.size(), rss);
  const long glEarly = peak(0, quarter, gl), glLate = peak(after.size() - quarter, after.size(), gl);
  const long fdEarly = peak(0, quarter, fds), fdLate = peak(after.size() - quarter, after.size(), fds);
  std::printf("spindrift_soak: %d frames in %.1f s on %s\n", frames, samples.back().seconds,
              renderer.glRenderer().c_str());
  std::printf("  RSS peak %ld MiB early, %ld MiB late (%+ld KiB)\n", rssEarly / 1024, rssLate / 1024,
              rssLate - rssEarly);
  std::printf("  GL objects %ld early, %ld late; open descriptors %ld early, %ld late\n", glEarly, glLate,
              fdEarly, fdLate);
  const bool flat = rssLate - rssEarly <= 8 * 1024 && glLate <= glEarly && fdLate <= fdEarly;
  std::printf("  %s\n", flat ? "flat" : "GREW");
  return flat ? 0 : 1;
}
