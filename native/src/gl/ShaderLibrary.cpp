#include "gl/ShaderLibrary.h"

#include <dlfcn.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include "spindrift/Error.h"

namespace spindrift {
namespace {

std::string readText(const std::filesystem::path& path) {
  std::ifstream stream(path);
  if (!stream) throw Error("cannot read shader " + path.string());
  std::stringstream text;
  text << stream.rdbuf();
  return text.str();
}

void expandInto(const std::filesystem::path& directory, const std::string& file,
                std::vector<std::string>& files, std::ostringstream& out, int depth) {
  if (depth > 16) throw Error("shader " + file + ": includes nest deeper than 16 (a cycle?)");
  const int sourceNumber = int(files.size());
  files.push_back(file);
  static const std::regex includeLine(R"(^\s*#\s*include\s+\"([^\"]+)\"\s*$)");
  std::istringstream lines(readText(directory / file));
  int lineNumber = 0;
  bool versionSeen = false;
  for (std::string line; std::getline(lines, line);) {
    ++lineNumber;
    std::smatch match;
    if (std::regex_match(line, match, includeLine)) {
      const std::string included = match[1].str();
      bool already = false;
      for (const auto& name : files)
        already = already || name == included;
      if (!already) expandInto(directory, included, files, out, depth + 1);
      out << "#line " << lineNumber + 1 << " " << sourceNumber << "\n";
      continue;
    }
    out << line << "\n";
    // GLSL wants #version first; number the lines after it so messages match the file.
    if (!versionSeen && line.find("#version") != std::string::npos) {
      versionSeen = true;
      out << "#line " << lineNumber + 1 << " " << sourceNumber << "\n";
    }
  }
}

// Mesa writes "0:12(5): error", NVIDIA "0(12) : error": both become "lib/frame.glsl:12: error".
std::string nameSourcesInLog(const std::string& log, const std::vector<std::string>& files) {
  static const std::regex location(R"((^|\n)(\d+)(?::(\d+)\(\d+\)|\((\d+)\)\s*):?)");
  std::string result;
  auto begin = std::sregex_iterator(log.begin(), log.end(), location);
  std::size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const std::smatch& match = *it;
    const std::size_t index = std::stoul(match[2].str());
    const std::string line = match[3].matched ? match[3].str() : match[4].str();
    result += log.substr(last, std::size_t(match.position(0)) - last);
    result += match[1].str() + (index < files.size() ? files[index] : match[2].str()) + ":" + line + ":";
    last = std::size_t(match.position(0) + match.length(0));
  }
  return result + log.substr(last);
}

GLenum stageFromFile(const std::string& file) {
  const std::string extension = std::filesystem::path(file).extension().string();
  if (extension == ".vert") return GL_VERTEX_SHADER;
  if (extension == ".frag") return GL_FRAGMENT_SHADER;
  if (extension == ".comp") return GL_COMPUTE_SHADER;
  if (extension == ".geom") return GL_GEOMETRY_SHADER;
  throw Error("shader " + file + ": unknown stage (expected .vert, .geom, .frag or .comp)");
}

}  // namespace

std::filesystem::path findShaderDirectory() {
  if (const char* overridden = std::getenv("SPINDRIFT_SHADER_DIR"); overridden && *overridden) {
    if (!std::filesystem::is_directory(overridden))
      throw Error(std::string("SPINDRIFT_SHADER_DIR=") + overridden + " is not a directory");
    return overridden;
  }
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&findShaderDirectory), &info) && info.dli_fname) {
    const std::filesystem::path library = std::filesystem::canonical(info.dli_fname);
    const std::filesystem::path candidate = library.parent_path().parent_path() / "share/spindrift/shaders";
    if (std::filesystem::is_directory(candidate)) return candidate;
    throw Error("Spindrift's shaders are not at " + candidate.string() + " (set SPINDRIFT_SHADER_DIR)");
  }
  throw Error("cannot locate the Spindrift library to find its shaders (set SPINDRIFT_SHADER_DIR)");
}

void requireShaderSources(const std::filesystem::path& directory) {
  readText(directory / "fullscreen.vert");
}

ShaderLibrary::ShaderLibrary(std::filesystem::path directory, ProgramCache cache)
    : directory_(std::move(directory)), cache_(std::move(cache)) {}

std::string ShaderLibrary::expandedSource(const std::string& file, std::vector<std::string>& files) const {
  std::ostringstream out;
  expandInto(directory_, file, files, out, 0);
  return out.str();
}

ProgramObject ShaderLibrary::program(const std::vector<std::string>& stageFiles,
                                     const std::vector<std::string>& defines) const {
  std::vector<std::string> sources;
  std::vector<std::vector<std::string>> sourceFiles(stageFiles.size());
  for (std::size_t stage = 0; stage < stageFiles.size(); ++stage) {
    std::string source = expandedSource(stageFiles[stage], sourceFiles[stage]);
    // After the #version line; the #line that follows it keeps the numbering of the file's lines.
    const std::size_t version = source.find("#version");
    const std::size_t afterVersion = version == std::string::npos ? 0 : source.find('\n', version) + 1;
    std::string definitions;
    for (const std::string& name : defines)
      definitions += "#define " + name + "\n";
    source.insert(afterVersion, definitions);
    // The file name is part of the key: the same text as another stage type is another program.
    sources.push_back(stageFiles[stage] + "\n" + source);
  }
  std::string key;
  for (const std::string& source : sources)
    key += source + '\0';
  ProgramObject& made = programs_[key];
  if (made) return made;
  if ((made = cache_.load(sources))) return made;
  made = compile(stageFiles, sources, sourceFiles);
  ++cache_.counts.compiled;
  cache_.store(sources, made.id());
  return made;
}

ProgramObject ShaderLibrary::compile(const std::vector<std::string>& stageFiles,
                                     const std::vector<std::string>& sources,
                                     const std::vector<std::vector<std::string>>& sourceFiles) const {
  ProgramObject program(glCreateProgram());
  std::vector<GLuint> shaders;
  auto deleteShaders = [&] {
    for (GLuint shader : shaders)
      glDeleteShader(shader);
  };
  for (std::size_t stage = 0; stage < stageFiles.size(); ++stage) {
    const std::string& file = stageFiles[stage];
    const std::vector<std::string>& files = sourceFiles[stage];
    const std::string source = sources[stage].substr(file.size() + 1);
    const GLuint shader = glCreateShader(stageFromFile(file));
    shaders.push_back(shader);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint compiled = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
    if (!compiled) {
      GLint length = 0;
      glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
      std::string log(std::size_t(std::max(length, 1)), '\0');
      glGetShaderInfoLog(shader, length, nullptr, log.data());
      deleteShaders();
      throw Error("shader " + file + " does not compile:\n" + nameSourcesInLog(log.c_str(), files));
    }
    glAttachShader(program.id(), shader);
  }
  if (cache_.enabled()) glProgramParameteri(program.id(), GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
  glLinkProgram(program.id());
  deleteShaders();  // Attached shaders live on inside the program until it is deleted.
  GLint linked = GL_FALSE;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &linked);
  if (!linked) {
    GLint length = 0;
    glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program.id(), length, nullptr, log.data());
    std::string names;
    for (const auto& file : stageFiles)
      names += (names.empty() ? "" : " + ") + file;
    throw Error("shaders " + names + " do not link:\n" + std::string(log.c_str()));
  }
  return program;
}

GLint uniformLocation(GLuint program, const char* name) {
  const GLint location = glGetUniformLocation(program, name);
  if (location < 0) throw Error(std::string("shader program has no active uniform ") + name);
  return location;
}

}  // namespace spindrift
