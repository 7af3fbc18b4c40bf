// The output rule's checks (core/output_path.h) and atomic writes into special files and through
// symbolic links (core/atomic_file.h).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <iterator>

#include "file_contents.h"
#include "radarslam/core/atomic_file.h"
#include "radarslam/core/errors.h"
#include "radarslam/core/output_path.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using radarslam::InputError;

using radarslam::test::readFileBytes;

TEST(OutputPath, NoOverlapBetweenInputAndOutput) {
  radarslam::test::TempDir tmp;
  fs::create_directories(tmp / "data" / "gt");
  EXPECT_THROW(radarslam::checkNoOverlap(tmp / "data", tmp / "data"), InputError);
  EXPECT_THROW(radarslam::checkNoOverlap(tmp / "data", tmp / "data/"), InputError);
  EXPECT_THROW(radarslam::checkNoOverlap(tmp / "data", tmp / "data" / "gt" / "x.tum"), InputError);
  EXPECT_THROW(radarslam::checkNoOverlap(tmp / "data" / "gt", tmp / "data"), InputError);
  EXPECT_NO_THROW(radarslam::checkNoOverlap(tmp / "data", tmp / "data" / "exports", true));
  EXPECT_NO_THROW(radarslam::checkNoOverlap(tmp / "data", tmp / "data2"));
  fs::create_directory_symlink("data", tmp / "alias");  // the same directory under another name
  EXPECT_THROW(radarslam::checkNoOverlap(tmp / "alias", tmp / "data" / "m"), InputError);
}

TEST(OutputPath, TwoOutputsOfOneRunAreDistinctFiles) {
  radarslam::test::TempDir tmp;
  fs::create_directory(tmp / "out");
  EXPECT_NO_THROW(radarslam::checkDistinctOutputs(tmp / "out" / "a.tum", tmp / "out" / "b.csv", "--steps"));
  EXPECT_THROW(radarslam::checkDistinctOutputs(tmp / "out" / "a.tum", tmp / "out" / "a.tum", "--steps"),
               InputError);
  EXPECT_THROW(
      radarslam::checkDistinctOutputs(tmp / "out" / "a.tum", tmp / "out" / ".." / "out" / "a.tum", "--steps"),
      InputError);
  fs::create_directory_symlink("out", tmp / "alias");  // the same directory under another name
  EXPECT_THROW(radarslam::checkDistinctOutputs(tmp / "out" / "a.tum", tmp / "alias" / "a.tum", "--steps"),
               InputError);
  fs::create_symlink("a.tum", tmp / "out" / "link.tum");  // a dangling link to the first output
  try {
    radarslam::checkDistinctOutputs(tmp / "out" / "a.tum", tmp / "out" / "link.tum", "--steps");
    ADD_FAILURE() << "a link to the first output was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--steps names the same file as"), std::string::npos) << e.what();
  }
}

TEST(OutputPath, MapOutputReplacesOnlyAMap) {
  radarslam::test::TempDir tmp;
  fs::create_directories(tmp / "map");
  std::ofstream(tmp / "map" / "manifest.yaml") << "format_version: 1\n";
  fs::create_directories(tmp / "other" / "keep");
  fs::create_directories(tmp / "empty");
  std::ofstream(tmp / "file") << "x";
  EXPECT_NO_THROW(radarslam::checkMapOutput(tmp / "map", false));
  EXPECT_NO_THROW(radarslam::checkMapOutput(tmp / "new", false));
  EXPECT_THROW(radarslam::checkMapOutput(tmp / "other", true), InputError);
  EXPECT_THROW(radarslam::checkMapOutput(tmp / "empty", false), InputError);
  EXPECT_NO_THROW(radarslam::checkMapOutput(tmp / "empty", true));
  EXPECT_THROW(radarslam::checkMapOutput(tmp / "file", false), InputError);
  EXPECT_NO_THROW(radarslam::checkMapOutput(tmp / "file", true));
  EXPECT_THROW(radarslam::checkMapOutput(tmp / "file" / "sub", true), InputError);
  EXPECT_THROW(radarslam::checkMapOutput("", true), InputError);
}

TEST(OutputPath, FileOutput) {
  radarslam::test::TempDir tmp;
  std::ofstream(tmp / "file") << "x";
  EXPECT_NO_THROW(radarslam::checkFileOutput(tmp / "file"));
  EXPECT_NO_THROW(radarslam::checkFileOutput(tmp / "a" / "b" / "new.tum"));
  EXPECT_THROW(radarslam::checkFileOutput(tmp.path()), InputError);
  EXPECT_THROW(radarslam::checkFileOutput(tmp / "file" / "x.tum"), InputError);
  EXPECT_THROW(radarslam::checkFileOutput(""), InputError);
}

TEST(OutputPath, AtomicWriteGoesThroughASymlinkAndIntoAFifo) {
  radarslam::test::TempDir tmp;
  std::ofstream(tmp / "target.txt") << "old";
  fs::create_symlink("target.txt", tmp / "link.txt");
  radarslam::writeTextAtomically(tmp / "link.txt", "new");
  EXPECT_TRUE(fs::is_symlink(tmp / "link.txt"));
  EXPECT_EQ(readFileBytes(tmp / "target.txt"), "new");

  const fs::path fifo = tmp / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // the writer's open then returns
  ASSERT_GE(reader, 0);
  radarslam::writeTextAtomically(fifo, "through the pipe\n");
  char buf[64] = {};
  const ssize_t n = ::read(reader, buf, sizeof buf - 1);
  ::close(reader);
  EXPECT_EQ(std::string(buf, n > 0 ? static_cast<std::size_t>(n) : 0), "through the pipe\n");
  EXPECT_TRUE(fs::is_fifo(fifo));
}

}  // namespace
