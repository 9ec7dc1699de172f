#pragma once
// A command of dress-a-mesh: it adds its arguments to the app and runs when it is the one chosen.
// Errors are thrown (InputError, OutputError, ...); main maps them to exit codes (docs/cli.md).
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <nlohmann/json.hpp>

// The commands call every library by its plain names (each command file includes the headers it uses).
namespace dresskit::alignment {}
namespace dresskit::cloth {}
namespace dresskit::dressing {}
namespace dresskit::mannequin {}
namespace dresskit::mesh {}
namespace dresskit::pattern {}
namespace dresskit::report {}
namespace dresskit::segmentation {}
namespace dresskit::thickness {}

namespace dresskit::cli {
using namespace dresskit::alignment;
using namespace dresskit::cloth;
using namespace dresskit::dressing;
using namespace dresskit::mannequin;
using namespace dresskit::mesh;
using namespace dresskit::pattern;
using namespace dresskit::report;
using namespace dresskit::segmentation;
using namespace dresskit::thickness;
namespace fs = std::filesystem;
using json = nlohmann::json;

/// An option that shows its default in --help.
template <typename T>
CLI::Option* option_with_default(CLI::App* command, const std::string& name, T& value, const std::string& help) {
  return command->add_option(name, value, help)->capture_default_str();
}

/// A check for a number option: a finite value above zero ("--remesh: -1 is not a positive number";
/// CLI::PositiveNumber's message spells out the largest double). Text that is no number is left
/// to the option's conversion, a usage error as for every number option.
inline CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::size_t used = 0;
        double value = 0.0;
        try {
          value = std::stod(text, &used);
        } catch (const std::exception&) {
          return {};
        }
        if (used != text.size()) return {};
        return std::isfinite(value) && value > 0.0 ? std::string() : text + " is not a positive number";
      },
      "POSITIVE", "positive");
}

struct Command {
  CLI::App* command = nullptr;  ///< the subcommand, set by add_to
  virtual ~Command() = default;
  virtual void add_to(CLI::App& app) = 0;
  /// Returns the exit code.
  virtual int run() = 0;
};

}  // namespace dresskit::cli
