// Run folders (issue 11): run.json and checkpoints are replaced whole or not
// at all, and a folder holding a run is reused only when asked, and then
// only the run's own files go.
#include "gjkdem/io/run_observers.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <unistd.h>

namespace gjkdem::io {
namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& f) {
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct RunFolderTest : ::testing::Test {
  // One folder per test and process: ctest runs the tests side by side.
  fs::path dir = fs::temp_directory_path() /
                 ("gjkdem_run_folder_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                  "_" + std::to_string(::getpid()));
  void SetUp() override { fs::remove_all(dir), fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }
};

// A write that fails part-way (here: the temporary file cannot be made)
// leaves the previous run.json whole, where an in-place rewrite on a full
// disk left it truncated.
TEST_F(RunFolderTest, AFailedWriteLeavesThePreviousFileWhole) {
  const fs::path file = dir / "run.json";
  write_file_atomically(file, "{\"status\": \"running\"}\n");
  EXPECT_EQ(read(file), "{\"status\": \"running\"}\n");
  fs::create_directories(dir / "run.json.tmp");  // in the way of the temporary file
  EXPECT_THROW(write_file_atomically(file, "{\"status\": \"failed\", \"error\": \"disk full\"}\n"), std::exception);
  EXPECT_EQ(read(file), "{\"status\": \"running\"}\n");
}

TEST_F(RunFolderTest, OnlyTheRunsOwnFilesAreReplaced) {
  RunPaths p{dir};
  prepare_run_folder(p, false);  // empty: fine
  std::ofstream(p.trace()) << "time\n";
  std::ofstream(p.frames() / "frame_000000.vtk") << "x";
  std::ofstream(p.frames() / "notes.txt") << "mine";
  std::ofstream(dir / "data.csv") << "mine";
  EXPECT_THROW(prepare_run_folder(p, false), RunFolderError);
  EXPECT_TRUE(fs::exists(p.trace()));
  prepare_run_folder(p, true);
  EXPECT_FALSE(fs::exists(p.trace()));
  EXPECT_FALSE(fs::exists(p.frames() / "frame_000000.vtk"));
  EXPECT_TRUE(fs::exists(p.frames() / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir / "data.csv"));
}

TEST_F(RunFolderTest, AFolderIsLockedWhileARunUsesIt) {
  std::optional<RunFolderLock> first;
  first.emplace(dir);
  EXPECT_THROW(RunFolderLock second(dir), RunFolderError);
  first.reset();
  EXPECT_NO_THROW(RunFolderLock third(dir));
}

}  // namespace
}  // namespace gjkdem::io
