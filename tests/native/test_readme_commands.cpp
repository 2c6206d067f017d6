// Every command the README shows runs as written. The `spindrift` commands run for real, in a directory that
// holds the files they name (a tiny scene stands in for scene.json and the dam-break example's, whose bake
// takes minutes); the scripts that take minutes (install, build, bake, benchmark) must exist, be executable
// and, where they have one, accept their arguments with --help.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "TempDirectory.h"

namespace {

// The lines of the README's ```sh blocks, continuation lines joined and comments removed.
std::vector<std::string> readmeCommands() {
  std::ifstream readme(std::string(SPINDRIFT_SOURCE_DIR) + "/README.md");
  std::vector<std::string> commands;
  std::string line, pending;
  bool inShellBlock = false;
  while (std::getline(readme, line)) {
    if (line.rfind("```", 0) == 0) {
      inShellBlock = !inShellBlock && line == "```sh";
      continue;
    }
    if (!inShellBlock) continue;
    const std::size_t comment = line.find(" #");
    if (comment != std::string::npos) line = line.substr(0, comment);
    line = std::regex_replace(line, std::regex("^\\s+|\\s+$"), "");
    if (!line.empty() && line.back() == '\\') {
      pending += line.substr(0, line.size() - 1) + " ";
      continue;
    }
    line = pending + line;
    pending.clear();
    if (!line.empty()) commands.push_back(line);
  }
  return commands;
}

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

int runShell(const std::string& command, std::string* output) {
  TempDirectory logs;
  const std::string log = (logs.path() / "output.txt").string();
  const int status = std::system((command + " >" + log + " 2>&1").c_str());
  std::ifstream file(log);
  std::stringstream text;
  text << file.rdbuf();
  *output = text.str();
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A tiny scene: a few particles in front of a 16×12 camera, so even the README's 240-frame sequence is quick.
std::string tinyScene() {
  return R"({"version": 1, "frame": 1,
    "camera": {"width": 16, "height": 12, "fov_y_deg": 40, "position": [0, -3, 0], "target": [0, 0, 0],
               "up": [0, 0, 1]},
    "particles": [{"path": "particles.ply", "radius": 0.2}],
    "background": {"color": [0.2, 0.3, 0.4]}})";
}

const char* kParticles =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
    "z\nend_header\n"
    "0 0 0\n0.3 0 0\n0 0 0.3\n";

}  // namespace

TEST(ReadmeCommands, TheReadmeShowsCommands) {
  const std::vector<std::string> commands = readmeCommands();
  EXPECT_GE(commands.size(), 8u);
  int spindriftCommands = 0;
  for (const std::string& command : commands)
    spindriftCommands += startsWith(command, "spindrift ") || startsWith(command, "build/bin/spindrift ");
  EXPECT_GE(spindriftCommands, 5);
}

TEST(ReadmeCommands, SpindriftCommandsRunAsWritten) {
  const std::string cli = SPINDRIFT_CLI_PATH;
  const std::string cliDirectory = cli.substr(0, cli.rfind('/'));
  for (const std::string& command : readmeCommands()) {
    if (!startsWith(command, "spindrift ") && !startsWith(command, "build/bin/spindrift ")) continue;
    TempDirectory directory;
    for (const char* folder : {"", "examples/dam_break/"}) {
      directory.write(std::string(folder) + "scene.json", tinyScene());
      directory.write(std::string(folder) + "particles.ply", kParticles);
    }
    std::filesystem::create_directories(directory.path() / "out");  // scripts/render-example makes it.
    std::filesystem::create_directories(directory.path() / "build/bin");
    std::filesystem::create_symlink(cli, directory.path() / "build/bin/spindrift");
    std::string output;
    const int exitCode =
        runShell("cd '" + directory.path().string() + "' && PATH='" + cliDirectory + "':\"$PATH\" " + command,
                 &output);
    EXPECT_EQ(exitCode, 0) << command << "\n" << output;
  }
}

TEST(ReadmeCommands, ScriptsExistAndAcceptTheirArguments) {
  const std::string source = SPINDRIFT_SOURCE_DIR;
  for (const std::string& command : readmeCommands()) {
    if (startsWith(command, "spindrift ") || startsWith(command, "build/bin/spindrift ")) continue;
    const std::string program = command.substr(0, command.find(' '));
    const std::string path = source + "/" + program;
    EXPECT_EQ(access(path.c_str(), X_OK), 0) << command << ": " << program << " is not an executable file";
    if (startsWith(program, "tests/bench/")) {
      std::string output;
      EXPECT_EQ(runShell("cd '" + source + "' && " + command + " --help", &output), 0) << command << "\n"
                                                                                       << output;
    }
  }
}
