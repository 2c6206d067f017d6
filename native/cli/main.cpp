// `spindrift`: renders scene files from a shell, lists parameters, and reports the OpenGL it finds.
// Exit codes: 0 success, 1 a scene, file or rendering error (one line on stderr), 2 a usage error.

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>

#include "Progress.h"
#include "spindrift/Error.h"
#include "spindrift/Output.h"
#include "spindrift/Renderer.h"

namespace {

using namespace spindrift;

struct RenderOptions {
  std::string scenePath;
  std::string exrPath;
  std::string pngPath;
  std::string statsPath;
  std::string frames;
  std::vector<std::string> assignments;
  bool quiet = false;
  bool intermediate = false;
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

bool hasFramePattern(const std::string& path) { return path.find('#') != std::string::npos; }

// The frame's stats, with the radius of every liquid source and where it came from (the scene file, or the
// Mantaflow domain it was derived from) and the surface offset the frame was drawn with.
nlohmann::json statsJson(const RenderResult& result, const Scene& scene) {
  nlohmann::json stats = result.stats.toJson();
  nlohmann::json sources = nlohmann::json::array();
  for (const ParticleSource& source : scene.particles)
    if (source.role == ParticleRole::Liquid)
      sources.push_back({{"path", source.path.string()}, {"radius", source.radius}, {"radius_origin", source.radiusOrigin},
                         {"mantaflow_flat_offset", source.meshFlatOffset}});
  stats["liquid_sources"] = sources;
  stats["liquid_surface_offset_radii"] = scene.parameters.liquid.surface_offset;
  return stats;
}

int runRender(const RenderOptions& options) {
  // Usage errors first: a bad frame list is reported as such even when the scene is also wrong.
  const std::vector<int> requestedFrames = options.frames.empty() ? std::vector<int>{} : cli::parseFrameList(options.frames);
  Scene scene = loadScene(options.scenePath);
  applyAssignments(scene, options.assignments);
  const std::vector<int> frames = requestedFrames.empty() ? std::vector<int>{scene.frame} : requestedFrames;
  if (frames.size() > 1)
    for (const std::string* path : {&options.exrPath, &options.pngPath})
      if (!path->empty() && !hasFramePattern(*path))
        throw Error(*path + ": several frames need #### in the output name");

  Renderer renderer;
  renderer.setIntermediateLayers(options.intermediate);
  if (!options.quiet) std::fprintf(stderr, "spindrift: rendering on %s\n", renderer.glRenderer().c_str());
  cli::Progress progress(int(frames.size()), options.quiet);
  nlohmann::json allStats = nlohmann::json::array();
  for (int frame : frames) {
    const auto start = std::chrono::steady_clock::now();
    const RenderResult result = renderer.renderFrame(scene, frame);
    if (!options.exrPath.empty()) writeExr(result, pathForFrame(options.exrPath, frame));
    if (!options.pngPath.empty()) writePng(result, pathForFrame(options.pngPath, frame));
    if (!options.statsPath.empty() && hasFramePattern(options.statsPath)) {
      std::ofstream(pathForFrame(options.statsPath, frame)) << statsJson(result, scene).dump(2) << "\n";
    }
    allStats.push_back(statsJson(result, scene));
    progress.frameDone(frame, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  progress.finish();
  if (!options.statsPath.empty() && !hasFramePattern(options.statsPath)) {
    std::ofstream stats(options.statsPath);
    stats << (frames.size() == 1 ? allStats[0] : nlohmann::json{{"frames", allStats}}).dump(2) << "\n";
    if (!stats) throw Error(options.statsPath + ": cannot write the stats");
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
    table.push_back({{"key", row.key}, {"type", row.type}, {"default", row.defaultValue}, {"minimum", row.minimum},
                     {"maximum", row.maximum}, {"choices", row.choices}, {"doc", row.doc}});
  std::cout << table.dump(2) << "\n";
  return 0;
}

int runInfo() {
  Renderer renderer;
  std::cout << "OpenGL renderer: " << renderer.glRenderer() << "\nOpenGL version:  " << renderer.glVersion() << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Spindrift: screen-space liquid and foam rendering of particle simulations"};
  app.set_version_flag("--version", "spindrift 0.1.0");
  app.require_subcommand(1);

  RenderOptions render;
  CLI::App* renderCommand = app.add_subcommand("render", "Render frames of a scene file");
  renderCommand->add_option("scene", render.scenePath, "Scene file (JSON, version 1)")->required();
  renderCommand->add_option("-o,--output", render.exrPath, "Multilayer OpenEXR of every pass; #### = frame number");
  renderCommand->add_option("--png", render.pngPath, "The composite as 8-bit sRGB PNG; #### = frame number");
  renderCommand->add_option("--stats", render.statsPath, "Per-pass timings and particle counts as JSON");
  renderCommand->add_option("--frames", render.frames, "Frames to render: 12, 1-240, 1-240:2 or a comma list "
                                                       "(default: the scene's `frame`, else 1)");
  renderCommand->add_option("--set", render.assignments, "Override a parameter: key=value (value is JSON)");
  renderCommand->add_flag("-q,--quiet", render.quiet, "No progress output");
  renderCommand->add_flag("--intermediate", render.intermediate,
                          "Also write the depth layers before and after smoothing into the EXR");

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
