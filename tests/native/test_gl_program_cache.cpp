// The program binary cache (gl/ProgramCache): a program loaded from the cache computes what the compiled one
// does; a changed shader source or driver string recompiles; a corrupt or truncated cache file is ignored and
// rebuilt; an empty directory turns the cache off. Variants compiled with #defines are programs of their own.
#include <gtest/gtest.h>

#include <fstream>
#include <vector>

#include "TempDirectory.h"
#include "gl/GlThread.h"
#include "gl/ProgramCache.h"
#include "gl/ShaderLibrary.h"

using namespace spindrift;

namespace {

// A compute shader that writes lib/value.glsl's constant, so a test can tell which source a program came
// from.
const char* kWriter = R"(#version 450 core
#include "lib/value.glsl"
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Output { float result; };
#ifdef DOUBLED
const float kFactor = 2.0;
#else
const float kFactor = 1.0;
#endif
void main() { result = kValue * kFactor; }
)";

const char* kDriver = "Mesa\nllvmpipe (test)\n4.5 (Core Profile) Mesa";

struct Outcome {
  float value = 0.0f;  // What the program wrote.
  ProgramCacheCounts counts;
};

class GLProgramCache : public ::testing::Test {
 protected:
  void SetUp() override {
    shaders_.write("writer.comp", kWriter);
    setValue("1.5");
  }
  void setValue(const std::string& value) {
    shaders_.write("lib/value.glsl", "const float kValue = " + value + ";\n");
  }
  std::filesystem::path cacheDirectory() const { return cache_.path() / "programs"; }

  // Builds the program through a fresh library and cache (as a new process would) and runs it.
  Outcome build(const std::string& driver = kDriver, std::filesystem::path directory = {},
                const std::vector<std::string>& defines = {}) {
    if (directory.empty()) directory = cacheDirectory();
    return thread_.run([&] {
      const ShaderLibrary library(shaders_.path(), ProgramCache(directory, driver));
      const ProgramObject program = library.program({"writer.comp"}, defines);
      BufferObject output = createBuffer();
      glNamedBufferStorage(output.id(), sizeof(float), nullptr, GL_DYNAMIC_STORAGE_BIT);
      glUseProgram(program.id());
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, output.id());
      glDispatchCompute(1, 1, 1);
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      Outcome outcome;
      glGetNamedBufferSubData(output.id(), 0, sizeof(float), &outcome.value);
      checkGlError("running the cached program");
      outcome.counts = library.cacheCounts();
      return outcome;
    });
  }

  std::vector<std::filesystem::path> cacheFiles() const {
    std::vector<std::filesystem::path> files;
    if (std::filesystem::exists(cacheDirectory()))
      for (const auto& entry : std::filesystem::directory_iterator(cacheDirectory()))
        files.push_back(entry.path());
    return files;
  }

  TempDirectory shaders_, cache_;
  GlThread thread_;
};

}  // namespace

TEST_F(GLProgramCache, SecondBuildLoadsTheBinaryAndComputesTheSame) {
  const Outcome first = build();
  EXPECT_EQ(first.value, 1.5f);
  EXPECT_EQ(first.counts.compiled, 1);
  EXPECT_EQ(first.counts.loaded, 0);
  ASSERT_EQ(cacheFiles().size(), 1u);
  const Outcome second = build();
  EXPECT_EQ(second.value, 1.5f);
  EXPECT_EQ(second.counts.loaded, 1);
  EXPECT_EQ(second.counts.compiled, 0);
}

TEST_F(GLProgramCache, ChangedIncludedSourceRecompiles) {
  build();
  setValue("2.25");
  const Outcome changed = build();
  EXPECT_EQ(changed.value, 2.25f) << "a stale binary was used";
  EXPECT_EQ(changed.counts.compiled, 1);
  EXPECT_EQ(changed.counts.loaded, 0);
  EXPECT_EQ(cacheFiles().size(), 2u);
}

TEST_F(GLProgramCache, ChangedDriverStringRecompiles) {
  build();
  const Outcome otherDriver = build("Mesa\nllvmpipe (test)\n4.6 (Core Profile) Mesa 99");
  EXPECT_EQ(otherDriver.value, 1.5f);
  EXPECT_EQ(otherDriver.counts.compiled, 1);
  EXPECT_EQ(otherDriver.counts.loaded, 0);
}

TEST_F(GLProgramCache, CorruptFileIsIgnoredAndRebuilt) {
  build();
  ASSERT_EQ(cacheFiles().size(), 1u);
  const std::filesystem::path file = cacheFiles()[0];
  const auto size = std::filesystem::file_size(file);
  {
    // Flip one byte in the middle of the binary: the checksum no longer matches.
    std::fstream stream(file, std::ios::in | std::ios::out | std::ios::binary);
    stream.seekg(std::streamoff(size / 2));
    const char byte = char(stream.get());
    stream.seekp(std::streamoff(size / 2));
    stream.put(char(~byte));
  }
  const Outcome corrupt = build();
  EXPECT_EQ(corrupt.value, 1.5f);
  EXPECT_EQ(corrupt.counts.rejected, 1);
  EXPECT_EQ(corrupt.counts.compiled, 1);
  EXPECT_EQ(build().counts.loaded, 1) << "the rebuilt file is used next time";
}

TEST_F(GLProgramCache, TruncatedOrGarbageFilesAreIgnored) {
  build();
  const std::filesystem::path file = cacheFiles()[0];
  for (const std::string& contents : {std::string(), std::string("SPDPROG1"), std::string(4096, '\x5a')}) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << contents;
    const Outcome outcome = build();
    EXPECT_EQ(outcome.value, 1.5f);
    EXPECT_EQ(outcome.counts.rejected, 1) << contents.size() << " bytes";
    EXPECT_EQ(outcome.counts.compiled, 1);
  }
}

TEST_F(GLProgramCache, EmptyDirectoryTurnsTheCacheOff) {
  const std::filesystem::path none;
  const Outcome first = thread_.run([&] {
    const ShaderLibrary library(shaders_.path(), ProgramCache(none, kDriver));
    const ProgramObject program = library.program({"writer.comp"});
    return Outcome{0.0f, library.cacheCounts()};
  });
  EXPECT_EQ(first.counts.compiled, 1);
  EXPECT_TRUE(cacheFiles().empty());
}

TEST_F(GLProgramCache, DefinesMakeVariantsOfTheirOwnAndKeepTheFilesLineNumbers) {
  EXPECT_EQ(build().value, 1.5f);
  const Outcome doubled = build(kDriver, {}, {"DOUBLED"});
  EXPECT_EQ(doubled.value, 3.0f) << "the define did not reach the shader";
  EXPECT_EQ(doubled.counts.compiled, 1) << "the variant was taken for the plain program";
  const Outcome again = build(kDriver, {}, {"DOUBLED"});
  EXPECT_EQ(again.value, 3.0f);
  EXPECT_EQ(again.counts.loaded, 1);
  EXPECT_EQ(build().value, 1.5f);

  // An error on the file's third line is reported there, defines or not.
  shaders_.write("broken.comp",
                 "#version 450 core\nlayout(local_size_x = 1) in;\nvoid main() { undeclared = 1; }\n");
  const std::string message = thread_.run([&] {
    const ShaderLibrary library(shaders_.path());
    try {
      library.program({"broken.comp"}, {"DOUBLED", "ANOTHER"});
    } catch (const std::exception& error) {
      return std::string(error.what());
    }
    return std::string();
  });
  EXPECT_NE(message.find("broken.comp:3"), std::string::npos) << message;
}

TEST_F(GLProgramCache, OneLibraryGivesTheSameSourcesOneProgram) {
  // Passes that ask for the same program share it (each sets its uniforms before drawing): it is loaded or
  // compiled once, and kept while any pass holds it.
  thread_.run([&] {
    const ShaderLibrary library(shaders_.path(), ProgramCache(cacheDirectory(), kDriver));
    const long before = liveGlObjectCount(GlObjectType::Program);
    ProgramObject first = library.program({"writer.comp"});
    const ProgramObject second = library.program({"writer.comp"});
    const ProgramObject doubled = library.program({"writer.comp"}, {"DOUBLED"});
    EXPECT_EQ(first.id(), second.id());
    EXPECT_NE(first.id(), doubled.id());
    EXPECT_EQ(library.cacheCounts().compiled + library.cacheCounts().loaded, 2);
    EXPECT_EQ(liveGlObjectCount(GlObjectType::Program), before + 2);
    first.reset();
    EXPECT_NE(second.id(), 0u);
    GLint linked = 0;
    glGetProgramiv(second.id(), GL_LINK_STATUS, &linked);
    EXPECT_EQ(linked, GL_TRUE) << "the library and the other pass still hold it";
  });
}
