#pragma once
// Writing a command's outputs so that they appear together or not at all: everything is written
// into a fresh temporary folder beside DIR, then moved into DIR (created when missing); on any
// failure the temporary folder is removed and DIR is left as it was. DIR keeps a list of what the
// last run wrote (.dress-a-mesh-outputs); a later run removes the files of that list it does not
// write again, so that no output of an earlier run is left beside a new one.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace dresskit::cli {

/// Calls write(folder) with the temporary folder, then moves what it wrote into dir. Throws
/// OutputError naming dir when a folder cannot be made or a file moved; InputError, before anything
/// is moved, when an output would replace one of `inputs`; rethrows write's errors.
void write_folder(const std::string& dir, const std::function<void(const std::filesystem::path&)>& write,
                  const std::vector<std::string>& inputs = {});

/// Before any work: throws InputError when dir is one of `inputs` (a file given as the output
/// folder), OutputError when dir exists and is not a folder, or does not exist and lies under a
/// file, or when the folder it is written in cannot be written.
void check_output_folder(const std::string& dir, const std::vector<std::string>& inputs);

}  // namespace dresskit::cli
