#pragma once
// A command of dress-a-mesh: it adds its arguments to the app and runs when it is the one chosen.
// Errors are thrown (InputError, OutputError, ...); main maps them to exit codes (docs/cli.md).
#include <CLI/CLI.hpp>

namespace dresskit::cli {

struct Command {
  CLI::App* command = nullptr;  ///< the subcommand, set by add_to
  virtual ~Command() = default;
  virtual void add_to(CLI::App& app) = 0;
  /// Returns the exit code.
  virtual int run() = 0;
};

}  // namespace dresskit::cli
