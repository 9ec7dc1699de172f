#pragma once
// Where the real test data lives: DRESSKIT_DATA_DIR, else ../shared/data beside the project.
// With CI=true a missing data folder fails the test; elsewhere the test is skipped with a message.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "dresskit/testing/data.h"

namespace dresskit::test {

inline std::string data_dir() { return testing::data_dir(); }
inline bool in_ci() { return testing::in_ci(); }

/// A fresh empty directory under the system temporary folder, removed by the destructor. Named by
/// the test's suite and name, the process and a count: tests of one name in two suites (run side
/// by side by ctest -j) never share one.
class TempDir {
 public:
  TempDir() {
    static int made = 0;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("dresskit_" + (info ? std::string(info->test_suite_name()) + "_" + info->name() : std::string("test")) +
             "_" + std::to_string(::getpid()) + "_" + std::to_string(made++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace dresskit::test

/// Skips (or, under CI=true, fails) the current test when the real data folder is missing.
#define DRESSKIT_REQUIRE_DATA()                                                             \
  do {                                                                                      \
    if (!std::filesystem::is_directory(::dresskit::test::data_dir())) {                     \
      if (::dresskit::test::in_ci()) {                                                      \
        FAIL() << "data folder missing under CI: " << ::dresskit::test::data_dir();         \
      }                                                                                     \
      GTEST_SKIP() << "data folder not found: " << ::dresskit::test::data_dir()             \
                   << " (set DRESSKIT_DATA_DIR)";                                           \
    }                                                                                       \
  } while (0)
