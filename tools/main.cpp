// dress-a-mesh: the command-line front of dresskit. Each command parses its arguments and calls the
// libraries (tools/commands/); errors come back as exceptions, mapped here to the exit codes of
// docs/cli.md.
#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>
#include <vector>

#include "commands/align.h"
#include "commands/clean.h"
#include "commands/demo.h"
#include "commands/dress.h"
#include "commands/info.h"
#include "commands/pattern.h"
#include "commands/segment.h"
#include "commands/simulate.h"
#include "commands/thickness.h"
#include "dresskit/mesh/errors.h"

using namespace dresskit;

namespace {

/// One line on stderr and the exit code for each kind of error.
int fail(const std::string& message, ExitCode code) {
  std::cerr << "dress-a-mesh: " << message << "\n";
  return static_cast<int>(code);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dress-a-mesh: dress 3D human bodies in garments (dresskit)"};
  app.set_version_flag("--version", std::string("dress-a-mesh ") + DRESSKIT_VERSION);
  app.require_subcommand(1);

  std::vector<std::unique_ptr<cli::Command>> commands;
  commands.push_back(std::make_unique<cli::DressCommand>());
  commands.push_back(std::make_unique<cli::DemoCommand>());
  commands.push_back(std::make_unique<cli::InfoCommand>());
  commands.push_back(std::make_unique<cli::CleanCommand>());
  commands.push_back(std::make_unique<cli::SegmentCommand>());
  commands.push_back(std::make_unique<cli::AlignCommand>());
  commands.push_back(std::make_unique<cli::SimulateCommand>());
  commands.push_back(std::make_unique<cli::ThicknessCommand>());
  commands.push_back(std::make_unique<cli::PatternCommand>());
  for (const auto& c : commands) c->add_to(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ValidationError& e) {  // a value its option's check refuses: out of range
    return fail(e.what(), ExitCode::bad_input);
  } catch (const CLI::ParseError& e) {
    return fail(std::string(e.what()) + " (see --help)", ExitCode::usage);
  }

  try {
    for (const auto& c : commands)
      if (*c->command) return c->run();
  } catch (const CLI::ValidationError& e) {
    return fail(std::string(e.what()) + " (see --help)", ExitCode::usage);
  } catch (const InputError& e) {
    return fail(e.what(), ExitCode::bad_input);
  } catch (const OutputError& e) {
    return fail(e.what(), ExitCode::output_failed);
  } catch (const std::exception& e) {
    return fail(std::string("internal error: ") + e.what(), ExitCode::internal_error);
  }
  return static_cast<int>(ExitCode::internal_error);
}
