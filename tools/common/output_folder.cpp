#include "common/output_folder.h"

#include <unistd.h>

#include <fstream>
#include <set>

#include "dresskit/mesh/errors.h"

namespace dresskit::cli {
namespace fs = std::filesystem;
namespace {
const char* const kOutputList = ".dress-a-mesh-outputs";
}  // namespace

void write_folder(const std::string& dir, const std::function<void(const fs::path&)>& write,
                  const std::vector<std::string>& inputs) {
  const fs::path target = fs::absolute(dir).lexically_normal();
  const fs::path temp = target.parent_path() /
                        ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()));
  std::error_code ec;
  fs::remove_all(temp, ec);
  if (!fs::create_directories(temp, ec) || ec)
    throw OutputError(dir + ": cannot create directory: " + ec.message());
  try {
    write(temp);
    for (const auto& entry : fs::directory_iterator(temp)) {
      const fs::path out = target / entry.path().filename();
      for (const std::string& input : inputs) {
        std::error_code same;
        if (!input.empty() && fs::exists(out) && fs::equivalent(out, input, same))
          throw InputError(out.string() + ": refusing to overwrite the input " + input);
      }
    }
    // What this run wrote, listed in the folder: the next run into it removes what it listed and
    // does not write again (a segmentation into fewer parts leaves no part files of the last one),
    // and nothing it did not write.
    std::set<std::string> written;
    for (const auto& entry : fs::directory_iterator(temp)) written.insert(entry.path().filename().string());
    {
      std::ofstream list(temp / kOutputList);
      for (const std::string& name : written) list << name << '\n';
      if (!list) throw OutputError(dir + ": cannot write " + kOutputList);
    }
    if (!fs::exists(target)) {
      fs::rename(temp, target);
      return;
    }
    if (!fs::is_directory(target)) throw OutputError(dir + ": exists and is not a directory");
    std::ifstream previous(target / kOutputList);
    for (std::string name; std::getline(previous, name);) {
      const fs::path old = target / name;
      if (name.empty() || name.find('/') != std::string::npos || name == "." || name == ".." ||
          written.count(name))
        continue;
      bool input = false;
      for (const std::string& in : inputs) input = input || (fs::exists(old) && fs::equivalent(old, in, ec));
      if (!input) fs::remove_all(old, ec);
    }
    for (const auto& entry : fs::directory_iterator(temp))
      fs::rename(entry.path(), target / entry.path().filename());
    fs::remove(temp);
  } catch (const fs::filesystem_error& e) {
    fs::remove_all(temp, ec);
    throw OutputError(dir + ": " + e.code().message());
  } catch (...) {
    fs::remove_all(temp, ec);
    throw;
  }
}

void check_output_folder(const std::string& dir, const std::vector<std::string>& inputs) {
  std::error_code ec;
  // The outputs are written beside DIR, in its parent (made where missing): a folder to be made
  // under a file, or in a folder that cannot be written, is said before any work rather than after.
  for (fs::path up = fs::absolute(dir, ec).parent_path(); !up.empty(); up = up.parent_path()) {
    if (fs::exists(up, ec)) {
      if (!fs::is_directory(up, ec)) throw OutputError(dir + ": cannot be made: " + up.string() + " is not a directory");
      // Tried rather than asked (access() says yes to root on any folder): a folder made and removed.
      const fs::path probe = up / (".dress-a-mesh-probe-" + std::to_string(::getpid()));
      const bool made = fs::create_directory(probe, ec);
      if (ec) throw OutputError(dir + ": cannot be written: no folder can be made in " + up.string() + " (" + ec.message() + ")");
      if (made) fs::remove(probe, ec);
      break;
    }
    if (up == up.parent_path()) break;
  }
  if (!fs::exists(dir, ec)) return;
  for (const std::string& input : inputs) {
    std::error_code same;
    if (!input.empty() && fs::equivalent(dir, input, same))
      throw InputError(dir + ": the output folder is an input; give another -o");
  }
  if (!fs::is_directory(dir, ec)) throw OutputError(dir + ": exists and is not a directory");
}

}  // namespace dresskit::cli
