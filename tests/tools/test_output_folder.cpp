// Writing outputs together or not at all: the lock a run holds on its output folder, what killed
// runs leave behind, names the file system refuses and inputs named as outputs, all found before
// any work.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>

#include "common/output_folder.h"
#include "dresskit/mesh/errors.h"
#include "test_data.h"

namespace dresskit::cli {
namespace {
namespace fs = std::filesystem;

int entries(const fs::path& folder) {
  return static_cast<int>(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

void write_one(const fs::path& folder) { std::ofstream(folder / "a.txt") << "a\n"; }

TEST(OutputFolder, AnEmptyNameIsBadInput) {
  EXPECT_THROW((void)check_output_folder("", {}), InputError);
  EXPECT_THROW(write_folder("", write_one), InputError);
}

TEST(OutputFolder, ASecondRunIntoTheSameFolderIsRefusedWhileTheFirstHoldsIt) {
  const test::TempDir dir;
  const std::string out = dir.file("out");
  {
    const OutputLock first = check_output_folder(out, {});
    EXPECT_THROW((void)check_output_folder(out, {}), OutputError);
    EXPECT_NO_THROW((void)check_output_folder(dir.file("other"), {}));  // another folder beside it
    write_folder(out, write_one);
  }
  EXPECT_NO_THROW((void)check_output_folder(out, {}));
  // Nothing of the locks is left beside the folder: only the folder written.
  EXPECT_EQ(entries(dir.path()), 1);
  EXPECT_TRUE(fs::exists(fs::path(out) / "a.txt"));
}

TEST(OutputFolder, WhatAKilledRunLeftIsRemovedByTheNextRun) {
  const test::TempDir dir;
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);  // its process id now names no process
  const fs::path stale = dir.path() / (".dress-a-mesh-tmp-" + std::to_string(child));
  fs::create_directories(stale / "sub");
  std::ofstream(stale / "sub" / "dressed.glb") << "partial";
  const fs::path alive = dir.path() / (".dress-a-mesh-tmp-" + std::to_string(::getppid()));  // a live process's
  fs::create_directories(alive);
  write_folder(dir.file("out"), write_one);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(alive));
}

TEST(OutputFolder, AFailedWriteLeavesNothing) {
  const test::TempDir dir;
  EXPECT_THROW(write_folder(dir.file("out"),
                            [](const fs::path& folder) {
                              write_one(folder);
                              throw OutputError("disk full");
                            }),
               OutputError);
  EXPECT_EQ(entries(dir.path()), 0);
}

TEST(OutputFolder, ANameTooLongIsFoundBeforeAnyWorkAndTheLongestAllowedIsWritten) {
  const test::TempDir dir;
  const long name_max = ::pathconf(dir.path().c_str(), _PC_NAME_MAX);
  ASSERT_GT(name_max, 10);
  EXPECT_THROW((void)check_output_folder(dir.file(std::string(static_cast<std::size_t>(name_max) + 1, 'a')), {}),
               OutputError);
  const std::string longest = dir.file(std::string(static_cast<std::size_t>(name_max), 'b'));
  {
    const OutputLock lock = check_output_folder(longest, {});
    write_folder(longest, write_one);
  }
  EXPECT_TRUE(fs::exists(fs::path(longest) / "a.txt"));
}

TEST(OutputFolder, AnInputNamedAsAnOutputInTheFolderIsRefusedBeforeAnyWork) {
  const test::TempDir dir;
  const std::string input = dir.file("report.json");
  std::ofstream(input) << "{}";
  EXPECT_THROW((void)check_output_folder(dir.path().string(), {input}, {"report.json"}), InputError);
  EXPECT_NO_THROW((void)check_output_folder(dir.path().string(), {input}, {"dressed.glb"}));
  EXPECT_THROW((void)check_output_folder(input, {input}), InputError);  // the input as the folder
}

}  // namespace
}  // namespace dresskit::cli
