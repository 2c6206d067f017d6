#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "gl/GlObjects.h"
#include "gl/ProgramCache.h"

namespace spindrift {

/// Where the shaders are: $SPINDRIFT_SHADER_DIR if set, else `../share/spindrift/shaders` beside the
/// directory of the Spindrift library file (the same shape in the build tree and an install). Never the
/// working directory. Throws Error listing the places looked at.
std::filesystem::path findShaderDirectory();

/// Throws the Error a program's build would throw ("cannot read shader ...") when the directory's first
/// shader cannot be read: a Renderer reports a wrong directory when it is made, though its programs are built
/// later.
void requireShaderSources(const std::filesystem::path& directory);

/// Loads GLSL from the shader directory, resolves `#include "lib/name.glsl"` (each file once) with a `#line`
/// after every switch of file, and reports compile errors with file names and lines instead of source-string
/// numbers. With a ProgramCache, a program whose sources and driver are unchanged is loaded from its binary
/// instead of compiled.
class ShaderLibrary {
 public:
  explicit ShaderLibrary(std::filesystem::path directory, ProgramCache cache = ProgramCache({}, ""));

  /// Compiles and links one program from stage files named by extension: .vert, .geom, .frag, .comp. Asked
  /// again for the same sources, the library gives the program it made the first time.
  /// `defines` are #defined in every stage, after #version: a shader compiled in several variants (llvmpipe
  /// runs both sides of a branch on a uniform, so a mode switched by a uniform costs every mode the others'
  /// work too; liquid_shadow.frag).
  ProgramObject program(const std::vector<std::string>& stageFiles,
                        const std::vector<std::string>& defines = {}) const;
  /// The source of one stage after includes are resolved; `files` receives the name of each source-string
  /// number used in `#line` directives.
  std::string expandedSource(const std::string& file, std::vector<std::string>& files) const;

  const std::filesystem::path& directory() const { return directory_; }
  /// How many programs were loaded from the cache, compiled, or rebuilt after a rejected cache file.
  const ProgramCacheCounts& cacheCounts() const { return cache_.counts; }

 private:
  ProgramObject compile(const std::vector<std::string>& stageFiles, const std::vector<std::string>& sources,
                        const std::vector<std::vector<std::string>>& sourceFiles) const;

  std::filesystem::path directory_;
  mutable ProgramCache cache_;  // Loading a program does not change what the library gives.
  mutable std::map<std::string, ProgramObject> programs_;  // by their stages' sources
};

/// The location of a uniform; throws Error when the program has no active uniform of that name.
GLint uniformLocation(GLuint program, const char* name);

}  // namespace spindrift
