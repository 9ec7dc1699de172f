#pragma once
// Writing a command's outputs so that they appear together or not at all: everything is written
// into a fresh temporary folder beside DIR, then moved into DIR (created when missing); on any
// failure the temporary folder is removed and DIR is left as it was. Termination signals wait while
// the outputs are written and moved (a run interrupted then ends once they are in place or removed);
// a temporary folder left by a killed run is removed by the next run writing beside it. DIR keeps a
// list of what the last run wrote (.dress-a-mesh-outputs); a later run removes the files of that list
// it does not write again, so that no output of an earlier run is left beside a new one.
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

/// Held by a run from before its work until its outputs are written: another run into the same
/// folder meanwhile is refused (OutputError). Released when destroyed.
class OutputLock {
 public:
  OutputLock() = default;
  explicit OutputLock(const std::string& dir);
  OutputLock(OutputLock&& other) noexcept;
  OutputLock& operator=(OutputLock&& other) noexcept;
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  ~OutputLock();

 private:
  int fd_ = -1;
  std::filesystem::path file_;
};

/// Before any work: throws InputError when dir is empty, is one of `inputs` (a file given as the
/// output folder) or when one of `inputs` lies in dir under one of the names in `outputs` (the files
/// the run writes there); OutputError when dir's name is longer than its file system allows, when dir
/// exists and is not a folder, or does not exist and lies under a file, when the folder it is written
/// in cannot be written, or when another run is writing into it. Returns the lock the run holds.
[[nodiscard]] OutputLock check_output_folder(const std::string& dir, const std::vector<std::string>& inputs,
                                             const std::vector<std::string>& outputs = {});

}  // namespace dresskit::cli
