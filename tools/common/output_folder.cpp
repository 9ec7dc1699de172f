#include "common/output_folder.h"

#include <unistd.h>

#include "dresskit/mesh/errors.h"

namespace dresskit::cli {
namespace fs = std::filesystem;

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
    if (!fs::exists(target)) {
      fs::rename(temp, target);
      return;
    }
    if (!fs::is_directory(target)) throw OutputError(dir + ": exists and is not a directory");
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

}  // namespace dresskit::cli
