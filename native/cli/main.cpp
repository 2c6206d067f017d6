// `spindrift`: renders scene files from a shell, lists parameters, and reports the OpenGL it finds.
// Exit codes (cli/Sequence.h, docs/reliability.md): 0 success, 1 a scene, file or rendering error (one line
// on stderr), 2 a usage error, 3 frames failed under --keep-going, 128 + signal when stopped by SIGINT or
// SIGTERM.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <future>
#include <iostream>
#include <memory>
#include <optional>

#include <sys/resource.h>

#include <CLI/CLI.hpp>

#include "Heap.h"
#include "Progress.h"
#include "Sequence.h"
#include "spindrift/Error.h"
#include "spindrift/Output.h"
#include "spindrift/Renderer.h"
#include "spindrift/Threads.h"

namespace {

using namespace spindrift;

struct RenderOptions {
  std::string scenePath;
  std::string exrPath;
  std::string pngPath;
  std::string statsPath;
  std::string frames;
  std::vector<std::string> assignments;
  std::vector<std::string> layers;
  bool quiet = false;
  bool intermediate = false;
  bool skipExisting = false;
  bool keepGoing = false;
  bool populateHeap = true;
  int threads = 0;  // 0: all cores
  ExrOptions exr;   // every layer, 32-bit float, ZIP unless --exr-half or --exr-compression
};

void applyAssignments(Scene& scene, const std::vector<std::string>& assignments) {
  for (const std::string& assignment : assignments) {
    const std::size_t equals = assignment.find('=');
    if (equals == std::string::npos) throw Error("--set " + assignment + ": expected key=value");
    const std::string key = assignment.substr(0, equals), text = assignment.substr(equals + 1);
    nlohmann::json value;
    try {
      value = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error&) {
      value = text;  // A bare word is a string, so `--set liquid.smoothing=bilateral` needs no quotes.
    }
    setParameter(scene.parameters, key, value);
  }
}

// What the whole process has used so far: its minor page faults and its CPU time in user and system mode.
struct ProcessUsage {
  long pageFaults = 0;
  double userMilliseconds = 0.0, systemMilliseconds = 0.0;
};

ProcessUsage processUsage() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto milliseconds = [](const timeval& time) { return time.tv_sec * 1e3 + time.tv_usec * 1e-3; };
  return {usage.ru_minflt, milliseconds(usage.ru_utime), milliseconds(usage.ru_stime)};
}

bool hasFramePattern(const std::string& path) {
  return path.find('#') != std::string::npos;
}

// The frame's stats, with the radius of every liquid source and where it came from (the scene file, or the
// Mantaflow domain it was derived from) and the surface offset the frame was drawn with.
nlohmann::json statsJson(const RenderResult& result, const Scene& scene, const nlohmann::json& process) {
  nlohmann::json stats = result.stats.toJson();
  stats["process"] = process;
  nlohmann::json sources = nlohmann::json::array();
  for (const ParticleSource& source : scene.particles)
    if (source.role == ParticleRole::Liquid)
      sources.push_back({{"path", source.path.string()},
                         {"radius", source.radius},
                         {"radius_origin", source.radiusOrigin},
                         {"mantaflow_flat_offset", source.meshFlatOffset},
                         {"mantaflow_mesh_kernel_radius", source.meshKernelRadius}});
  stats["liquid_sources"] = sources;
  stats["liquid_surface_offset_radii"] = scene.parameters.liquid.surface_offset;
  stats["liquid_mesh_kernel_radius_radii"] = scene.parameters.liquid.mesh_kernel_radius;
  return stats;
}

int runRender(const RenderOptions& options) {
  // Usage errors first: a bad frame list is reported as such even when the scene is also wrong.
  const std::vector<int> requestedFrames =
      options.frames.empty() ? std::vector<int>{} : cli::parseFrameList(options.frames);
  Scene scene = loadScene(options.scenePath);
  applyAssignments(scene, options.assignments);
  const std::vector<int> frames = requestedFrames.empty() ? std::vector<int>{scene.frame} : requestedFrames;
  if (frames.size() > 1)
    for (const std::string* path : {&options.exrPath, &options.pngPath})
      if (!path->empty() && !hasFramePattern(*path))
        throw Error(*path + ": several frames need #### in the output name");

  std::optional<WorkerThreadLimit> threadLimit;
  if (options.threads > 0) threadLimit.emplace(options.threads);
  // The first frame's heap is mapped while the renderer starts its GL context (docs/frame-cost.md, session
  // 46).
  std::optional<cli::HeapPopulation> heap;
  if (options.populateHeap) heap.emplace(cli::firstFrameHeapBytes(scene.camera.width, scene.camera.height));
  Renderer renderer;
  nlohmann::json heapStats = {{"populated", false}, {"why_not", "--no-populate-heap"}};
  if (heap) {
    heap->wait();
    heapStats = {{"populated", heap->populatedBytes() > 0},
                 {"populated_mib", double(heap->populatedBytes()) / double(1 << 20)},
                 {"huge_page_mib", double(heap->hugePageBytes()) / double(1 << 20)},
                 {"transparent_huge_pages", cli::transparentHugePagesMode()},
                 {"ms", heap->milliseconds()}};
    if (!heap->notPopulated().empty()) heapStats["why_not"] = heap->notPopulated();
  }
  renderer.setIntermediateLayers(options.intermediate);
  std::vector<std::string> layers = options.layers;
  if (!layers.empty() && !options.pngPath.empty() &&
      std::find(layers.begin(), layers.end(), "composite") == layers.end())
    layers.push_back("composite");  // The PNG is the composite.
  renderer.setLayers(layers);
  if (!options.quiet) std::fprintf(stderr, "spindrift: rendering on %s\n", renderer.glRenderer().c_str());
  cli::Progress progress(int(frames.size()), options.quiet);
  nlohmann::json allStats = nlohmann::json::array();
  cli::StopSignals stopSignals;
  std::vector<int> failedFrames;
  // Frame N's files are written on another thread while frame N+1 renders. A write's error is reported with
  // its frame when the next frame (or the end) waits for it; a stop signal waits for the write in flight, so
  // every file the sequence leaves is complete. "frame N done" is printed only once N's files are on disk:
  // farm wrappers and people read it as "this frame will be skipped if the job is rerun".
  std::future<void> pendingWrite;
  int pendingFrame = 0;
  double pendingSeconds = 0.0;
  auto finishPendingWrite = [&]() -> bool {  // False: the sequence stops.
    if (!pendingWrite.valid()) return true;
    try {
      pendingWrite.get();
      progress.frameDone(pendingFrame, pendingSeconds);
      return true;
    } catch (const std::exception& error) {
      if (frames.size() == 1) throw;
      std::fprintf(stderr, "\nspindrift: error: frame %d: %s\n", pendingFrame, error.what());
      failedFrames.push_back(pendingFrame);
      return options.keepGoing;
    }
  };
  for (int frame : frames) {
    if (cli::StopSignals::received()) break;
    const std::vector<std::filesystem::path> outputs = cli::perFrameOutputs(
        {options.exrPath, options.pngPath, options.statsPath}, frame, frames.size() == 1);
    if (options.skipExisting && cli::allExist(outputs)) {
      progress.frameSkipped(frame);
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    const ProcessUsage before = processUsage();
    std::shared_ptr<const RenderResult> result;
    try {
      result = std::make_shared<const RenderResult>(renderer.renderFrame(scene, frame));
    } catch (const std::exception& error) {
      if (frames.size() == 1) throw;
      std::fprintf(stderr, "\nspindrift: error: frame %d: %s\n", frame, error.what());
      if (!options.keepGoing) {
        finishPendingWrite();
        return cli::kExitError;
      }
      failedFrames.push_back(frame);
      continue;
    }
    if (!finishPendingWrite()) return cli::kExitError;
    if (cli::StopSignals::received()) break;  // The frame in flight is dropped before any of it is written.
    // Only now, with the previous frame's write finished: a frame listed twice (or two frames sharing a path)
    // would otherwise delete the temporary the write in flight is about to rename.
    for (const std::filesystem::path& output : outputs)
      cli::removeStaleTemporaries(output);
    // The process's page faults and CPU time while the frame rendered (every thread's; the previous frame's
    // write included), and on the first frame rendered, the heap mapped for it.
    const ProcessUsage after = processUsage();
    nlohmann::json process = {{"page_faults", after.pageFaults - before.pageFaults},
                              {"user_ms", after.userMilliseconds - before.userMilliseconds},
                              {"system_ms", after.systemMilliseconds - before.systemMilliseconds}};
    if (allStats.empty()) process["heap"] = heapStats;
    allStats.push_back(statsJson(*result, scene, process));
    pendingFrame = frame;
    pendingWrite = std::async(std::launch::async, [&options, &scene, result, frame, process] {
      if (!options.exrPath.empty()) writeExr(*result, pathForFrame(options.exrPath, frame), options.exr);
      if (!options.pngPath.empty()) writePng(*result, pathForFrame(options.pngPath, frame));
      if (!options.statsPath.empty() && hasFramePattern(options.statsPath))
        cli::writeTextFile(pathForFrame(options.statsPath, frame),
                           statsJson(*result, scene, process).dump(2) + "\n");
    });
    pendingSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  if (!finishPendingWrite()) return cli::kExitError;
  progress.finish();
  if (!options.statsPath.empty() && !hasFramePattern(options.statsPath) && !allStats.empty())
    cli::writeTextFile(
        options.statsPath,
        (frames.size() == 1 ? allStats[0] : nlohmann::json{{"frames", allStats}}).dump(2) + "\n");
  if (const int signalNumber = cli::StopSignals::received()) {
    std::fprintf(stderr, "spindrift: stopped by signal %d; every file written is complete\n", signalNumber);
    return 128 + signalNumber;
  }
  if (!failedFrames.empty()) {
    std::string list;
    for (int frame : failedFrames)
      list += (list.empty() ? "" : ",") + std::to_string(frame);
    std::fprintf(stderr, "spindrift: error: %zu of %zu frames failed: %s\n", failedFrames.size(),
                 frames.size(), list.c_str());
    return cli::kExitFramesFailed;
  }
  return 0;
}

int runParams(bool markdown) {
  if (markdown) {
    std::cout << parametersMarkdown();
    return 0;
  }
  nlohmann::json table = nlohmann::json::array();
  for (const ParameterInfo& row : parameterTable())
    table.push_back({{"key", row.key},
                     {"type", row.type},
                     {"default", row.defaultValue},
                     {"minimum", row.minimum},
                     {"maximum", row.maximum},
                     {"choices", row.choices},
                     {"doc", row.doc}});
  std::cout << table.dump(2) << "\n";
  return 0;
}

int runInfo() {
  Renderer renderer;
  std::cout << "OpenGL renderer: " << renderer.glRenderer() << "\nOpenGL version:  " << renderer.glVersion()
            << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  cli::keepTheHeap();
  CLI::App app{"Spindrift: screen-space liquid and foam rendering of particle simulations"};
  app.set_version_flag("--version", "spindrift 0.1.0");
  app.require_subcommand(1);

  RenderOptions render;
  CLI::App* renderCommand = app.add_subcommand("render", "Render frames of a scene file");
  renderCommand->add_option("scene", render.scenePath, "Scene file (JSON, version 1)")->required();
  renderCommand->add_option("-o,--output", render.exrPath,
                            "Multilayer OpenEXR of every pass; #### = frame number");
  renderCommand->add_option("--png", render.pngPath, "The composite as 8-bit sRGB PNG; #### = frame number");
  renderCommand->add_option("--stats", render.statsPath, "Per-pass timings and particle counts as JSON");
  renderCommand->add_option("--frames", render.frames,
                            "Frames to render: 12, 1-240, 1-240:2 or a comma list "
                            "(default: the scene's `frame`, else 1)");
  renderCommand->add_option("--set", render.assignments, "Override a parameter: key=value (value is JSON)");
  renderCommand
      ->add_option("--layers", render.layers,
                   "Layers to compute and write, comma-separated (default: all): composite, liquid, "
                   "liquid_splash, liquid_class, depth, normal, thickness, refraction_uv, "
                   "transmittance, reflection, foam, foam_spray, foam_surface, foam_bubble, "
                   "foam_shadow, foam_irradiance, foam_thickness, liquid_shadow, caustics, liquid_sky "
                   "(the last three when the scene has lights)")
      ->delimiter(',');
  renderCommand->add_flag("-q,--quiet", render.quiet, "No progress output");
  renderCommand->add_flag("--intermediate", render.intermediate,
                          "Also write the depth layers before and after smoothing into the EXR");
  renderCommand->add_flag("--skip-existing", render.skipExisting,
                          "Skip frames whose output files all exist (resume a stopped sequence)");
  renderCommand->add_flag("--keep-going", render.keepGoing,
                          "Go on after a frame fails; exit with 3 at the end if any did");
  renderCommand->add_flag("!--no-populate-heap", render.populateHeap,
                          "Leave the first frame's heap pages to fault in at first use (for measuring)");
  renderCommand
      ->add_option("--threads", render.threads, "Worker threads of the CPU preparation (default: all)")
      ->check(CLI::PositiveNumber);
  // Writing every layer as 32-bit float with ZIP at OpenEXR's level 4 cost about 100 ms a frame at 480x270 on
  // 2 cores, 16 times that at 1920x1080; level 1 about half (docs/farm.md). The write overlaps the next
  // frame's render but takes its CPU.
  renderCommand
      ->add_option("--exr-compression", render.exr.compression,
                   "OpenEXR compression of -o (default: " + ExrOptions{}.compression + ")")
      ->check(CLI::Validator(
          [](std::string& value) {
            return exrCompressionIsValid(value) ? std::string() : "unknown EXR compression \"" + value + "\"";
          },
          "NAME[:LEVEL]"));
  renderCommand->add_flag("--exr-half", render.exr.halfColor,
                          "Colour layers of -o as 16-bit half float (depths and refraction_uv stay 32-bit)");

  bool markdown = false;
  CLI::App* paramsCommand = app.add_subcommand("params", "List every parameter with its default (JSON)");
  paramsCommand->add_flag("--markdown", markdown, "Print docs/parameters.md instead");

  CLI::App* infoCommand = app.add_subcommand("info", "Create an OpenGL context and say what it is");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : 2;
  }
  try {
    if (renderCommand->parsed()) {
      if (render.exrPath.empty() && render.pngPath.empty() && render.statsPath.empty())
        throw Error("nothing to write: give -o, --png or --stats");
      return runRender(render);
    }
    if (paramsCommand->parsed()) return runParams(markdown);
    if (infoCommand->parsed()) return runInfo();
  } catch (const std::invalid_argument& error) {
    std::fprintf(stderr, "spindrift: error: %s\n", error.what());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "\nspindrift: error: %s\n", error.what());
    return 1;
  }
  return 0;
}
