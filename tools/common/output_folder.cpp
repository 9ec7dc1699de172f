#include "common/output_folder.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>

#include "dresskit/mesh/errors.h"

namespace dresskit::cli {
namespace fs = std::filesystem;
namespace {
const char* const kOutputList = ".dress-a-mesh-outputs";
/// The temporary folder a run writes into is named by this prefix and the run's process id, and
/// the lock a run holds by this prefix and its output folder's hash: of fixed length, so that any
/// output folder name its file system allows has them beside it.
const std::string kTempPrefix = ".dress-a-mesh-tmp-";
const std::string kLockPrefix = ".dress-a-mesh-lock-";

/// Removes what killed runs left in `folder`: temporary folders of processes that no longer exist,
/// and lock files nobody holds.
void remove_stale(const fs::path& folder) {
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(kTempPrefix, 0) == 0) {
      char* rest = nullptr;
      const long pid = std::strtol(name.c_str() + kTempPrefix.size(), &rest, 10);
      if (pid > 0 && *rest == '\0' && pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
        std::error_code ignored;
        fs::remove_all(it->path(), ignored);
      }
    } else if (name.rfind(kLockPrefix, 0) == 0) {
      const int fd = ::open(it->path().c_str(), O_RDWR | O_CLOEXEC);
      if (fd < 0) continue;
      if (::flock(fd, LOCK_EX | LOCK_NB) == 0) ::unlink(it->path().c_str());
      ::close(fd);
    }
  }
}

/// Termination signals wait while it lives: the outputs are then either all in place or removed
/// when a pending signal ends the process.
class SignalsHeld {
 public:
  SignalsHeld() {
    sigset_t held;
    sigemptyset(&held);
    for (int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaddset(&held, s);
    pthread_sigmask(SIG_BLOCK, &held, &before_);
  }
  ~SignalsHeld() { pthread_sigmask(SIG_SETMASK, &before_, nullptr); }
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  sigset_t before_;
};

/// The nearest folder above `path` (or `path` itself) that exists.
fs::path existing_ancestor(const fs::path& path) {
  std::error_code ec;
  fs::path up = path;
  while (!up.empty() && !fs::exists(up, ec) && up != up.parent_path()) up = up.parent_path();
  return up;
}
}  // namespace

void write_folder(const std::string& dir, const std::function<void(const fs::path&)>& write,
                  const std::vector<std::string>& inputs) {
  if (dir.empty()) throw InputError("-o: the output folder name is empty");
  const SignalsHeld held;
  const fs::path target = fs::absolute(dir).lexically_normal();
  const fs::path temp = target.parent_path() / (kTempPrefix + std::to_string(::getpid()));
  std::error_code ec;
  remove_stale(existing_ancestor(target.parent_path()));
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

OutputLock::OutputLock(const std::string& dir) {
  const fs::path target = fs::absolute(dir).lexically_normal();
  // In the nearest folder that exists (dir and its parents may be made only when written), named
  // by the whole path's hash.
  const fs::path up = existing_ancestor(target.parent_path());
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016zx", std::hash<std::string>()(target.string()));
  file_ = up / (kLockPrefix + hash);
  // A run ending unlinks its lock file: a lock taken on a file unlinked meanwhile is taken again.
  for (int attempt = 0; attempt < 3; ++attempt) {
    fd_ = ::open(file_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw OutputError(dir + ": cannot be written: no file can be made in " + up.string());
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      fd_ = -1;
      throw OutputError(dir + ": another run is writing into this folder; wait for it to end or give another -o");
    }
    struct stat held {}, named {};
    if (::fstat(fd_, &held) == 0 && ::stat(file_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev)
      return;
    ::close(fd_);
    fd_ = -1;
  }
  throw OutputError(dir + ": another run is writing into this folder; wait for it to end or give another -o");
}

OutputLock::OutputLock(OutputLock&& other) noexcept : fd_(other.fd_), file_(std::move(other.file_)) { other.fd_ = -1; }

OutputLock& OutputLock::operator=(OutputLock&& other) noexcept {
  if (this != &other) {
    this->~OutputLock();
    fd_ = other.fd_;
    file_ = std::move(other.file_);
    other.fd_ = -1;
  }
  return *this;
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ::unlink(file_.c_str());
  ::close(fd_);
  fd_ = -1;
}

OutputLock check_output_folder(const std::string& dir, const std::vector<std::string>& inputs,
                               const std::vector<std::string>& outputs) {
  if (dir.empty()) throw InputError("-o: the output folder name is empty");
  std::error_code ec;
  const fs::path target = fs::absolute(dir, ec).lexically_normal();
  // The outputs are written beside DIR, in its parent (made where missing): a folder to be made
  // under a file, or in a folder that cannot be written, is said before any work rather than after.
  const fs::path up = existing_ancestor(target.parent_path());
  if (!fs::is_directory(up, ec)) throw OutputError(dir + ": cannot be made: " + up.string() + " is not a directory");
  const long name_max = ::pathconf(up.c_str(), _PC_NAME_MAX);
  for (const fs::path& name : target.lexically_relative(up))
    if (name_max > 0 && static_cast<long>(name.string().size()) > name_max)
      throw OutputError(dir + ": cannot be made: a name of " + std::to_string(name.string().size()) +
                        " characters, longer than the " + std::to_string(name_max) + " its file system allows");
  // Tried rather than asked (access() says yes to root on any folder): a folder made and removed.
  const fs::path probe = up / (".dress-a-mesh-probe-" + std::to_string(::getpid()));
  const bool made = fs::create_directory(probe, ec);
  if (ec) throw OutputError(dir + ": cannot be written: no folder can be made in " + up.string() + " (" + ec.message() + ")");
  if (made) fs::remove(probe, ec);
  remove_stale(up);
  if (fs::exists(dir, ec)) {
    for (const std::string& input : inputs) {
      std::error_code same;
      if (input.empty()) continue;
      if (fs::equivalent(dir, input, same)) throw InputError(dir + ": the output folder is an input; give another -o");
      const fs::path in(input);
      if (std::find(outputs.begin(), outputs.end(), in.filename().string()) != outputs.end() &&
          fs::equivalent(fs::absolute(in, same).parent_path(), dir, same))
        throw InputError(input + ": an input named as an output the run writes into " + dir + "; give another -o");
    }
    if (!fs::is_directory(dir, ec)) throw OutputError(dir + ": exists and is not a directory");
  }
  return OutputLock(dir);
}

}  // namespace dresskit::cli
