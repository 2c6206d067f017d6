#pragma once
// Runs the `spindrift` command built beside the tests, as a shell would, and captures its stderr.

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "TempDirectory.h"

struct CommandResult {
  int exitCode;
  std::string stderrText;
};

inline CommandResult runCli(const std::string& arguments, const std::string& environment = "") {
  TempDirectory directory;
  const std::string errorsFile = (directory.path() / "stderr.txt").string();
  const std::string command = environment + " " + SPINDRIFT_CLI_PATH + " " + arguments + " 2>" + errorsFile;
  const int status = std::system(command.c_str());
  std::ifstream errors(errorsFile);
  std::stringstream text;
  text << errors.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}
