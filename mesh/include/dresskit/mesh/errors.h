#pragma once
// Error policy (see docs/cli.md for the exit codes):
// - assert() for programmer mistakes (a violated precondition inside the library);
// - InputError for bad input: a file, field or value that a user gave us. Its message is one line that
//   names the file (or field, or value) and the problem, ready to print as it is;
// - OutputError when a result cannot be written. Nothing partial is left behind in either case.
#include <stdexcept>
#include <string>

namespace dresskit {

/// Process exit codes of dress-a-mesh, documented in docs/cli.md.
enum class ExitCode : int {
  ok = 0,
  internal_error = 1,  ///< a bug or an unexpected exception
  bad_input = 2,       ///< unreadable, malformed or unusable input file or value
  output_failed = 3,   ///< an output could not be written (nothing partial is left)
  simulation_failed = 4,  ///< a simulation step blew up or went NaN; the last good state was written
  usage = 64,          ///< command-line usage error (unknown option, missing argument)
};

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace dresskit
