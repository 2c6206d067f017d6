#pragma once

#include <stdexcept>
#include <string>

namespace spindrift {

/// The one kind of failure Spindrift reports. Its message is a single line meant for the user (it names the
/// file, key or GL call at fault). Library code throws it and never aborts the host process; the CLI and the
/// Python module turn it into an exit code or a Python exception.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace spindrift
